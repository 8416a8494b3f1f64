//! Work kept on the calling thread: [`on_calling_thread`] runs a closure whose two-way splits
//! ([`join`]) run one after the other on the calling thread instead of on rayon's pool.
//!
//! For work on a thread outside the pool while the pool's threads run long jobs: a half handed
//! to the pool waits until a worker is free. The eigensolver's interval stream is such a thread
//! (it places and checks the solved intervals while the slices of the others run): on
//! `bunny-closed` with Galerkin masses its first placement waited 13 s for a worker, and the
//! stream's work piled up at the end of the run (`docs/performance.md`). The splits are the
//! same either way, so are the results, bit for bit.

use std::cell::Cell;

thread_local! {
    /// Whether this thread is inside [`on_calling_thread`].
    static ON_CALLING_THREAD: Cell<bool> = const { Cell::new(false) };
}

/// Runs `work` with every [`join`] it makes run on this thread, one half after the other.
pub(crate) fn on_calling_thread<T>(work: impl FnOnce() -> T) -> T {
    /// Restores the previous setting when dropped (also when `work` unwinds).
    struct Restore(bool);
    impl Drop for Restore {
        fn drop(&mut self) {
            ON_CALLING_THREAD.with(|on| on.set(self.0));
        }
    }
    let _restore = Restore(ON_CALLING_THREAD.with(|on| on.replace(true)));
    work()
}

/// `rayon::join(a, b)`, or `(a(), b())` inside [`on_calling_thread`].
pub(crate) fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
where
    A: FnOnce() -> RA + Send,
    B: FnOnce() -> RB + Send,
    RA: Send,
    RB: Send,
{
    if ON_CALLING_THREAD.with(Cell::get) {
        (a(), b())
    } else {
        rayon::join(a, b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Inside, both halves run on the calling thread in order; outside, `join` is rayon's (its
    /// halves may run elsewhere); the setting ends with the closure.
    #[test]
    fn joins_inside_run_on_the_calling_thread_in_order() {
        let here = std::thread::current().id();
        let order = std::sync::Mutex::new(Vec::new());
        let (a, b) = on_calling_thread(|| {
            join(
                || {
                    order.lock().unwrap().push('a');
                    std::thread::current().id()
                },
                || {
                    order.lock().unwrap().push('b');
                    std::thread::current().id()
                },
            )
        });
        assert_eq!((a, b), (here, here));
        assert_eq!(*order.lock().unwrap(), ['a', 'b']);
        assert!(!ON_CALLING_THREAD.with(Cell::get));
    }
}
