//! Criterion benchmarks of the geometry kernels: `cargo bench -p flexdem-geom`.
//! Inputs are seeded and generated outside the timed closures.

use criterion::criterion_main;

mod segment;
mod triangle;

criterion_main!(segment::benches, triangle::benches);
