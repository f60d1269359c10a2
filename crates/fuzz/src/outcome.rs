//! One input through one target: what came back, and whether it is a finding.

use std::cell::{Cell, RefCell};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;

use rslam_core::printable;

use crate::{Scratch, Target};

/// What one input did.
#[derive(Debug, PartialEq)]
pub enum Outcome {
    Accepted,
    /// Refused with this one-line error.
    Rejected(String),
    Found(Finding),
}

/// A bug: what kind, and the message that shows it.
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    pub kind: &'static str,
    pub message: String,
}

thread_local! {
    /// The message and place of the last panic on this thread, set by the hook.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
    /// Whether this thread is inside [`run_one`]'s `catch_unwind`.
    static IN_RUN: Cell<bool> = const { Cell::new(false) };
}

/// Inside [`run_one`], replaces the panic printout (one per input would flood the output) with a
/// record that [`run_one`] reads back; elsewhere (a failing test's own panic) the previous hook
/// prints as usual.
fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !IN_RUN.with(Cell::get) {
                return previous(info);
            }
            let place = info
                .location()
                .map_or(String::new(), |l| format!(" at {}:{}", l.file(), l.line()));
            let payload = info.payload();
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            LAST_PANIC.with(|last| *last.borrow_mut() = Some(format!("{message}{place}")));
        }));
    });
}

/// Runs `input` through `target`; a panic, a multi-line error and an error that does not name
/// the input's file are findings.
pub fn run_one(target: &Target, scratch: &Scratch, input: &[u8]) -> Outcome {
    install_panic_hook();
    IN_RUN.with(|r| r.set(true));
    let result = catch_unwind(AssertUnwindSafe(|| (target.check)(scratch, input)));
    IN_RUN.with(|r| r.set(false));
    match result {
        Ok(Ok(())) => Outcome::Accepted,
        Ok(Err(message)) if message.contains(['\n', '\r']) => Outcome::Found(Finding {
            kind: "multi-line error",
            message,
        }),
        Ok(Err(message)) if !names_its_file(target, scratch, &message) => Outcome::Found(Finding {
            kind: "error without the file's name",
            message,
        }),
        Ok(Err(message)) => Outcome::Rejected(message),
        Err(_) => Outcome::Found(Finding {
            kind: "panic",
            message: LAST_PANIC
                .with(|last| last.borrow_mut().take())
                .unwrap_or_else(|| "panic without a message".into()),
        }),
    }
}

/// Whether an error names a file or folder of the input: the input's file, the dataset folder
/// it is part of (a dataset without a frame rate is the folder's fault, not one file's), the
/// mesh whose material library it is.
fn names_its_file(target: &Target, scratch: &Scratch, message: &str) -> bool {
    target.file.is_none() || message.contains(&scratch.dir.display().to_string())
}

/// What a finding is counted once by: its kind and where it panicked, or its kind and the
/// message up to the first quoted text (the part that does not echo the input).
pub fn finding_key(finding: &Finding, scratch: &Scratch) -> String {
    let message = finding
        .message
        .replace(&scratch.dir.display().to_string(), "");
    let stable = match finding.kind {
        "panic" => message.rsplit(" at ").next().unwrap_or(""),
        _ => message.split(['\'', '"']).next().unwrap_or(""),
    };
    format!("{}: {stable}", finding.kind)
}

/// An error message with what varies from input to input taken out, so that errors of one kind
/// count once: its words (runs of three or more letters) that the input's letters do not spell,
/// in order. Echoed input (escaped or not), numbers and the scratch folder drop out; the error's
/// own wording stays.
pub fn signature(message: &str, input: &[u8], scratch: &Scratch) -> String {
    let message = message.replace(&scratch.dir.display().to_string(), "");
    // As errors quote it: control characters escaped (a line break reads `\n`).
    let letters: String = printable(&String::from_utf8_lossy(input))
        .chars()
        .filter(char::is_ascii_alphabetic)
        .collect();
    message
        .split(|c: char| !c.is_ascii_alphabetic())
        .filter(|word| word.len() >= 3 && !letters.contains(word))
        .take(24)
        .collect::<Vec<_>>()
        .join(" ")
}
