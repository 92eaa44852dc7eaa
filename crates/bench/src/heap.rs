//! The bytes the process's heap holds, where the binary can count them: a library cannot set
//! the global allocator, so the `flexdem` binary, which counts its allocations (the `cap`
//! crate's `Cap` around the system allocator), registers how to read the count here. The
//! benchmark's memory per element is then the heap the scene holds after its warm-up (its
//! state and every buffer kept from step to step), where the resident memory (`procfs`) also
//! counts pages the allocator kept from a previous case, or not.

use std::sync::OnceLock;

static HEAP_PROBE: OnceLock<fn() -> usize> = OnceLock::new();

/// Registers `probe`, which returns the bytes allocated on the heap now. Only the first
/// registration counts: returns whether this one did.
pub fn set_heap_probe(probe: fn() -> usize) -> bool {
    HEAP_PROBE.set(probe).is_ok()
}

/// The bytes allocated on the heap now, if a probe was registered.
pub fn heap_bytes() -> Option<u64> {
    HEAP_PROBE.get().map(|probe| probe() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The library's tests register no probe (the `flexdem` binary does: its bench test
    /// reads the heap column): no count, and the benchmark falls back on the resident memory.
    #[test]
    fn without_a_probe_there_is_no_count() {
        assert_eq!(heap_bytes(), None);
    }
}
