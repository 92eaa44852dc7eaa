//! Benchmarks of the triangle kernels: point–triangle (inside and outside the face),
//! segment–triangle and triangle–triangle. Inputs come from a seeded generator, outside the
//! timed closures; each iteration cycles through a batch of them.

use criterion::{criterion_group, Criterion};
use flexdem_geom::{
    closest_points_segment_triangle, closest_points_triangle_triangle, project_point_triangle, Vec3,
};
use std::hint::black_box;

/// Number of inputs cycled through by each benchmark.
const BATCH: usize = 1024;

/// A small seeded generator (SplitMix64) so that the inputs are the same on every run.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn vec3(&mut self) -> Vec3 {
        Vec3::new(self.next_f64(), self.next_f64(), self.next_f64()) * 2.0 - Vec3::repeat(1.0)
    }

    fn triangle(&mut self) -> [Vec3; 3] {
        [self.vec3(), self.vec3(), self.vec3()]
    }
}

fn kernels(c: &mut Criterion) {
    let mut rng = SplitMix64(0x5EED);
    let triangles: Vec<[Vec3; 3]> = (0..BATCH).map(|_| rng.triangle()).collect();
    // Points over the face (random positive weights plus a normal offset) and points anywhere.
    let inside: Vec<Vec3> = triangles
        .iter()
        .map(|t| {
            let w = [rng.next_f64() + 0.01, rng.next_f64() + 0.01, rng.next_f64() + 0.01];
            let n = (t[1] - t[0]).cross(&(t[2] - t[0])).normalize();
            (t[0] * w[0] + t[1] * w[1] + t[2] * w[2]) / (w[0] + w[1] + w[2])
                + n * (rng.next_f64() - 0.5)
        })
        .collect();
    let outside: Vec<Vec3> = (0..BATCH).map(|_| rng.vec3() * 2.0).collect();
    let segments: Vec<(Vec3, Vec3)> =
        (0..BATCH).map(|_| (rng.vec3() * 1.5, rng.vec3() * 1.5)).collect();
    let others: Vec<[Vec3; 3]> = (0..BATCH).map(|_| rng.triangle()).collect();

    let mut i = 0;
    c.bench_function("triangle/project_point_triangle_inside", |b| {
        b.iter(|| {
            i = (i + 1) % BATCH;
            let t = &triangles[i];
            black_box(project_point_triangle(black_box(&inside[i]), &t[0], &t[1], &t[2]))
        })
    });
    c.bench_function("triangle/project_point_triangle_outside", |b| {
        b.iter(|| {
            i = (i + 1) % BATCH;
            let t = &triangles[i];
            black_box(project_point_triangle(black_box(&outside[i]), &t[0], &t[1], &t[2]))
        })
    });
    c.bench_function("triangle/closest_points_segment_triangle", |b| {
        b.iter(|| {
            i = (i + 1) % BATCH;
            let (t, s) = (&triangles[i], &segments[i]);
            black_box(closest_points_segment_triangle(black_box(&s.0), &s.1, &t[0], &t[1], &t[2]))
        })
    });
    c.bench_function("triangle/closest_points_triangle_triangle", |b| {
        b.iter(|| {
            i = (i + 1) % BATCH;
            let (t, u) = (&triangles[i], &others[i]);
            black_box(closest_points_triangle_triangle(
                black_box(&t[0]),
                &t[1],
                &t[2],
                &u[0],
                &u[1],
                &u[2],
            ))
        })
    });
}

criterion_group!(benches, kernels);
