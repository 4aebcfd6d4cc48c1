//! Two independent computations side by side: the second on a scoped thread when the machine
//! has more than one core and the caller says the work is worth a thread, else both on the
//! calling thread. A thread that cannot be started is not an error: its work runs here.

use std::sync::OnceLock;

/// The environment variable that caps the threads ltikit starts (a positive integer; 1
/// keeps every computation on the calling thread).
pub(crate) const THREADS_VAR: &str = "LTIKIT_NUM_THREADS";

/// The cores this process may use (1 when unknown), capped by [`THREADS_VAR`] when it holds
/// a positive integer; asked once.
pub(crate) fn cores() -> usize {
    static CORES: OnceLock<usize> = OnceLock::new();
    *CORES.get_or_init(|| {
        let available = std::thread::available_parallelism().map_or(1, |c| c.get());
        let cap = std::env::var(THREADS_VAR)
            .ok()
            .and_then(|v| v.trim().parse::<usize>().ok())
            .filter(|&k| k > 0);
        cap.map_or(available, |k| k.min(available))
    })
}

/// (a(), b()), with `b` on a second thread when `beside` and there is a second core.
/// The results are the same either way (the two share nothing).
pub(crate) fn join<RA, RB>(
    beside: bool,
    a: impl FnOnce() -> RA,
    b: impl FnOnce() -> RB + Send,
) -> (RA, RB)
where
    RB: Send,
{
    if !beside || cores() < 2 {
        return (a(), b());
    }
    // `b` is taken by the thread only when it starts; a refused spawn leaves it here.
    let slot = std::sync::Mutex::new(Some(b));
    std::thread::scope(|scope| {
        let handle = std::thread::Builder::new().spawn_scoped(scope, || {
            let job = slot.lock().ok().and_then(|mut s| s.take());
            job.map(|f| f())
        });
        let ra = a();
        let rb = handle.ok().and_then(|h| h.join().ok()).flatten();
        let rb = match rb {
            Some(rb) => rb,
            None => match slot.lock().ok().and_then(|mut s| s.take()) {
                Some(f) => f(),
                // the thread took `b` and panicked: run nothing twice, re-raise
                None => std::panic::resume_unwind(Box::new("a parallel job panicked")),
            },
        };
        (ra, rb)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_results_beside_and_in_turn() {
        let v: Vec<u64> = (0..1000).collect();
        let a = || v.iter().sum::<u64>();
        let b = || v.iter().map(|x| x * x).sum::<u64>();
        assert_eq!(join(true, a, b), join(false, a, b));
        assert_eq!(join(true, a, b), (499_500, 332_833_500));
    }
}
