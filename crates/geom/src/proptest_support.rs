//! Proptest strategies for geometry inputs (feature `proptest-support`).
