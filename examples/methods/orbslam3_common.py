"""What the ORB-SLAM3 example methods share: their arguments (dataset, settings, estimate,
vocabulary), the checks on them, a tally of tracking states and the exit after saving."""
import argparse
import os
import sys


def fail(msg, code=2):
    """Prints the error and exits at once: once started, ORB-SLAM3's threads can hang a normal exit."""
    print(f"{os.path.basename(sys.argv[0])}: {msg}", file=sys.stderr)
    sys.stderr.flush()
    os._exit(code)


def argument_parser(doc, layout, settings=True):
    """--dataset, --settings (unless `settings` is False: a script that writes its own), --out and
    --vocabulary (default $ORBSLAM3_VOCABULARY)."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dataset", required=True, help=f"dataset folder ({layout} layout)")
    if settings:
        ap.add_argument("--settings", required=True, help="ORB-SLAM3 settings (the dataset's orbslam3*.yaml)")
    ap.add_argument("--out", required=True, help="estimate to write (TUM trajectory)")
    ap.add_argument("--vocabulary", default=os.environ.get("ORBSLAM3_VOCABULARY"),
                    help="ORBvoc.txt (default: $ORBSLAM3_VOCABULARY)")
    return ap


def parse_arguments(ap):
    """Parses (exits 2 on bad arguments) and checks that the vocabulary and any settings exist."""
    a = ap.parse_args()
    if not a.vocabulary or not os.path.isfile(a.vocabulary):
        fail(f"no ORB vocabulary at {a.vocabulary!r}: set ORBSLAM3_VOCABULARY or --vocabulary to ORBvoc.txt")
    if "settings" in vars(a) and not os.path.isfile(a.settings):
        fail(f"no settings file {a.settings}")
    return a


class StateTally:
    """How many frames ended in each tracking state (OK, LOST, ...)."""

    def __init__(self):
        self.counts = {}

    def add(self, result):
        name = result.state.name
        self.counts[name] = self.counts.get(name, 0) + 1

    def report(self, frames):
        print(f"{frames} frames, tracking states {self.counts}", file=sys.stderr)


def shut_down_and_exit(slam, states, save, never_tracked_hint=""):
    """Stops ORB-SLAM3, calls `save()` to write the estimate, and exits 0 at once: ORB-SLAM3's
    threads can hang at interpreter exit. Exits 1 when `save()` fails, or without saving when no
    frame was ever tracked (ORB-SLAM3 crashes saving an empty map)."""
    slam.shutdown()
    name = os.path.basename(sys.argv[0])
    code = 0
    if states.counts.get("OK", 0) == 0:
        print(f"{name}: ORB-SLAM3 tracked no frame, so there is no estimate{never_tracked_hint}", file=sys.stderr)
        code = 1
    else:
        try:
            save()
        except Exception as e:  # any failure: reported, and the exit must still skip the threads
            print(f"{name}: writing the estimate failed: {e}", file=sys.stderr)
            code = 1
    sys.stderr.flush()
    sys.stdout.flush()
    os._exit(code)
