//! Ctrl-C turned into a flag that progress reports check, so a run stops in order (no manifest
//! written, the same command resumes).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// The process's Ctrl-C flag; the handler is installed on the first call.
pub fn interrupt_flag() -> Arc<AtomicBool> {
    FLAG.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        let set = flag.clone();
        // Fails only if another handler is installed; then Ctrl-C keeps its default (exit).
        let _ = ctrlc::set_handler(move || set.store(true, Ordering::SeqCst));
        flag
    })
    .clone()
}
