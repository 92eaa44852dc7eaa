//! How finely the engine's parallel loops are split.

/// Fewest items a parallel task is given in a loop of cheap items (tens of nanoseconds each:
/// a hull, a prefilter test, a particle check): below it rayon does not split, since sending
/// work to another thread costs microseconds. Results do not depend on it (indexed maps and
/// collects keep their order).
pub(crate) const MIN_PARALLEL_CHEAP: usize = 1024;

/// Fewest items a parallel task is given in a loop of costly items (a contact's kernel or
/// law, up to a microsecond each).
pub(crate) const MIN_PARALLEL_COSTLY: usize = 64;
