//! Items worked on `jobs` at a time, in list order, until one says stop (Ctrl-C).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

/// Runs `work` on every item on `jobs` threads. Once an item returns `Err`, no further item is
/// started; the first such error comes back after every started item has ended, with the
/// results of those that finished (`None` for the rest).
pub fn run_queue<T: Sync, R: Send, E: Send>(
    items: &[T],
    jobs: usize,
    work: impl Fn(&T) -> Result<R, E> + Sync,
) -> (Vec<Option<R>>, Option<E>) {
    let next = AtomicUsize::new(0);
    let stopped = AtomicBool::new(false);
    let results = Mutex::new((0..items.len()).map(|_| None).collect::<Vec<_>>());
    let stop = Mutex::new(None);
    std::thread::scope(|scope| {
        for _ in 0..jobs.clamp(1, items.len().max(1)) {
            scope.spawn(|| {
                while !stopped.load(Ordering::SeqCst) {
                    let i = next.fetch_add(1, Ordering::SeqCst);
                    let Some(item) = items.get(i) else {
                        break;
                    };
                    match work(item) {
                        Ok(result) => {
                            results.lock().unwrap_or_else(|p| p.into_inner())[i] = Some(result)
                        }
                        Err(e) => {
                            stopped.store(true, Ordering::SeqCst);
                            stop.lock()
                                .unwrap_or_else(|p| p.into_inner())
                                .get_or_insert(e);
                        }
                    }
                }
            });
        }
    });
    (
        results.into_inner().unwrap_or_else(|p| p.into_inner()),
        stop.into_inner().unwrap_or_else(|p| p.into_inner()),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_item_runs_once_and_a_stop_starts_nothing_new() {
        let items: Vec<usize> = (0..50).collect();
        let (results, stop) = run_queue(&items, 4, |&i| Ok::<_, ()>(i * 2));
        assert!(stop.is_none());
        assert_eq!(
            results,
            items.iter().map(|i| Some(i * 2)).collect::<Vec<_>>()
        );

        let (results, stop) = run_queue(&items, 1, |&i| if i == 10 { Err("stop") } else { Ok(i) });
        assert_eq!(stop, Some("stop"));
        assert_eq!(
            results.iter().flatten().count(),
            10,
            "items after the stop never start"
        );
    }
}
