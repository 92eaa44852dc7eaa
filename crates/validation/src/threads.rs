//! Thread pools for the cases.

/// Runs `f` in a rayon pool of the machine's threads: for a case that runs many independent
/// small scenes (an ensemble of starts) from inside the one-thread pool every case runs in
/// (`runner::single_threaded`), one scene per task. The results do not depend on the number
/// of threads. Falls back to the current pool if a pool cannot be started.
pub fn on_all_threads<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    match rayon::ThreadPoolBuilder::new().build() {
        Ok(pool) => pool.install(f),
        Err(_) => f(),
    }
}
