#!/usr/bin/env bash
# Checks the user guide in docs/ (an mdBook): installs mdBook if it is missing, builds
# the book, checks every internal link and #anchor of docs/src/**/*.md, then runs every shell
# block (```sh, ```bash, ```console) of every page, in order, in a fresh temporary folder per page
# with rslam on PATH. A block tagged ```sh,norun is not run; its reason must stand beside it (a
# `#` comment as its first line, or "not run" in the line before it). Fails listing every broken
# link and every failed block (page, line, output); prints how many blocks ran and were skipped.
#   scripts/check-book.sh [BIN_DIR]     # BIN_DIR holds rslam (default target/release, else target/debug)
# BOOK_BLOCK_TIMEOUT (seconds, default 300) bounds each block.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD

bin_dir=${1:-}
if [ -z "$bin_dir" ]; then
  for dir in target/release target/debug; do
    if [ -x "$dir/rslam" ]; then bin_dir=$dir; break; fi
  done
fi
[ -n "$bin_dir" ] && [ -x "$bin_dir/rslam" ] || {
  echo "check-book: no rslam binary (give its folder, or build target/release or target/debug)" >&2
  exit 2
}
bin_dir=$(cd "$bin_dir" && pwd)

scripts/install-mdbook.sh
export PATH=$HOME/.cargo/bin:$PATH
mdbook build docs

PATH=$bin_dir:$PATH python3 - "$repo/docs/src" <<'PY'
import os, re, subprocess, sys, tempfile, unicodedata

src = sys.argv[1]
timeout = int(os.environ.get("BOOK_BLOCK_TIMEOUT", "300"))
FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})(.*)$")
SHELLS = {"sh", "bash", "console", "shell"}


def pages():
    for root, _, files in os.walk(src):
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(root, name)


def split(path):
    """(prose lines with their numbers, code blocks as (line, info, body lines))."""
    prose, blocks, block = [], [], None
    for number, line in enumerate(open(path, encoding="utf-8").read().split("\n"), 1):
        m = FENCE.match(line)
        if block is None:
            if m:
                block = (number, m.group(3).strip(), [], m.group(2))
            else:
                prose.append((number, line))
        elif m and m.group(2).startswith(block[3]) and not m.group(3).strip():
            blocks.append(block[:3])
            block = None
        else:
            block[2].append(line)
    return prose, blocks


def heading_ids(path):
    """The ids mdBook gives the page's headings: the heading's text without markup, lowercased
    (ASCII), whitespace to '-', everything but letters, digits, '_' and '-' dropped; a repeated
    id gets -1, -2, ..."""
    ids, seen = set(), {}
    for _, line in split(path)[0]:
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", m.group(1))  # links: their text
        text = re.sub(r"<[^>]+>", "", text).replace("`", "").replace("*", "")
        ident = "".join(
            c.lower() if c.isascii() else c
            for c in text
            if c.isalnum() or c in "_-" or c.isspace()
        )
        ident = re.sub(r"\s", "-", ident)
        if ident in seen:
            seen[ident] += 1
            ident = f"{ident}-{seen[ident]}"
        else:
            seen[ident] = 0
        ids.add(ident)
    return ids


LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")


def paragraphs(prose):
    """(first line number, text) of each run of non-blank prose lines: a link's text may break
    across lines. Code spans are blanked, keeping the line breaks."""
    runs, text, previous = [], [], None
    for number, line in prose + [(None, "")]:
        if text and (not line.strip() or number != previous + 1):
            joined = "\n".join(text)
            blanked = re.sub(r"`[^`]*`", lambda m: re.sub(r"[^\n]", " ", m[0]), joined)
            runs.append((previous - len(text) + 1, blanked))
            text = []
        if line.strip():
            text.append(line)
        previous = number
    return runs


broken, links = [], 0
for page in pages():
    rel = os.path.relpath(page, src)
    for first, text in paragraphs(split(page)[0]):
        for match in LINK.finditer(text):
            target, number = match[1], first + text.count("\n", 0, match.start(1))
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                continue
            links += 1
            path, _, anchor = target.partition("#")
            file = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            if not os.path.exists(file):
                broken.append(f"{rel}:{number}: {target}: no file {os.path.relpath(file, src)}")
            elif anchor and not file.endswith(".md"):
                broken.append(f"{rel}:{number}: {target}: an anchor into a file that is not a page")
            elif anchor and anchor not in heading_ids(file):
                broken.append(f"{rel}:{number}: {target}: no heading with id '{anchor}' in {os.path.relpath(file, src)}")
# The rule above must be mdBook's: compare it with the ids of the built pages.
book = os.path.join(os.path.dirname(src), "book")
for page in pages():
    html = os.path.join(book, os.path.relpath(page, src))[:-3] + ".html"
    if os.path.basename(page) == "SUMMARY.md" or not os.path.exists(html):
        continue
    built = set(re.findall(r'<h[1-6] id="([^"]*)"', open(html, encoding="utf-8").read()))
    if built != heading_ids(page):
        broken.append(f"{os.path.relpath(page, src)}: heading ids differ from mdBook's: "
                      f"{sorted(built ^ heading_ids(page))}")
print(f"links: {links} internal links checked, {len(broken)} broken")
for b in broken:
    print("  broken link: " + b)


def commands(info, body):
    """The script a block runs: a console block's `$ ` lines (with their continuations)."""
    if info.split(",")[0].strip() != "console":
        return "\n".join(body)
    script, going_on = [], False
    for line in body:
        if line.startswith("$ ") or going_on:
            script.append(line[2:] if line.startswith("$ ") and not going_on else line)
            going_on = line.rstrip().endswith("\\")
    return "\n".join(script)


ran = skipped = 0
failures, unreasoned = [], []
for page in pages():
    rel = os.path.relpath(page, src)
    lines = open(page, encoding="utf-8").read().split("\n")
    shell = [(n, info, body) for n, info, body in split(page)[1]
             if info.split(",")[0].strip() in SHELLS]
    if not shell:
        continue
    with tempfile.TemporaryDirectory(prefix="rslam-book-") as work:
        for number, info, body in shell:
            attributes = [a.strip() for a in info.split(",")[1:]]
            if "norun" in attributes:
                skipped += 1
                before = next((l for l in reversed(lines[: number - 1]) if l.strip()), "")
                first = next((l for l in body if l.strip()), "")
                if not first.lstrip().startswith("#") and "not run" not in before.lower():
                    unreasoned.append(f"{rel}:{number}: a norun block without its reason")
                continue
            ran += 1
            print(f"--- {rel}:{number}", flush=True)
            try:
                done = subprocess.run(["bash", "-eo", "pipefail", "-c", commands(info, body)],
                                      cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                      text=True, timeout=timeout)
                status, output = done.returncode, done.stdout
            except subprocess.TimeoutExpired as e:
                out = e.stdout or ""
                status = f"timeout after {timeout} s"
                output = out if isinstance(out, str) else out.decode(errors="replace")
            if status != 0:
                failures.append((rel, number, "\n".join(body), status, output))
                break  # the page's later blocks may build on this one
print(f"shell blocks: {ran} ran, {skipped} skipped as norun, {len(failures)} failed")
for rel, number, body, status, output in failures:
    print(f"\n=== FAILED {rel}:{number} (exit {status})\n{body}\n--- output:\n{output.rstrip()}")
for u in unreasoned:
    print("  " + u)
sys.exit(1 if broken or failures or unreasoned else 0)
PY
