//! Point–segment, segment–segment and swept-segment box kernels.
//!
//! Each benchmark cycles through a fixed array of inputs built by a seeded xorshift generator
//! before timing, so the branch predictor sees a realistic mix; the reported time is per call.

use criterion::{criterion_group, Criterion};
use flexdem_geom::{
    aabb_swept_segment, closest_points_segment_segment, project_point_segment, Vec3,
};
use std::hint::black_box;

/// Number of precomputed inputs each benchmark cycles through.
const N: usize = 1024;

/// Marsaglia's xorshift64, seeded: reproducible inputs without a dependency.
struct XorShift(u64);

impl XorShift {
    /// A float uniform in `[-1, 1)`.
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn vec3(&mut self) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next())
    }
}

fn segment_kernels(c: &mut Criterion) {
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    let points: Vec<[Vec3; 3]> = (0..N).map(|_| [rng.vec3(), rng.vec3(), rng.vec3()]).collect();
    let general: Vec<[Vec3; 4]> =
        (0..N).map(|_| [rng.vec3(), rng.vec3(), rng.vec3(), rng.vec3()]).collect();
    // Parallel pairs (b = a shifted and stretched), the branch that computes the overlap.
    let parallel: Vec<[Vec3; 4]> = (0..N)
        .map(|_| {
            let (a0, a1, b0) = (rng.vec3(), rng.vec3(), rng.vec3());
            let k = rng.next();
            [a0, a1, b0, b0 + (a1 - a0) * k]
        })
        .collect();
    let radii: Vec<f64> = (0..N).map(|_| 0.5 + 0.5 * rng.next()).collect();

    let mut i = 0;
    c.bench_function("segment/project_point_segment", |b| {
        b.iter(|| {
            let [p, a, s] = &points[i % N];
            i += 1;
            black_box(project_point_segment(black_box(p), black_box(a), black_box(s)))
        })
    });
    for (name, cases) in [("general", &general), ("parallel", &parallel)] {
        let mut i = 0;
        c.bench_function(&format!("segment/closest_points_segment_segment/{name}"), |b| {
            b.iter(|| {
                let [a0, a1, b0, b1] = &cases[i % N];
                i += 1;
                black_box(closest_points_segment_segment(
                    black_box(a0),
                    black_box(a1),
                    black_box(b0),
                    black_box(b1),
                ))
            })
        });
    }
    let mut i = 0;
    c.bench_function("segment/aabb_swept_segment", |b| {
        b.iter(|| {
            let [a, s, _] = &points[i % N];
            let r = radii[i % N];
            i += 1;
            black_box(aabb_swept_segment(black_box(a), black_box(s), black_box(r)))
        })
    });
}

criterion_group!(benches, segment_kernels);
