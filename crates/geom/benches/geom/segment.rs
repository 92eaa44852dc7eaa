use criterion::{criterion_group, Criterion};

fn kernels(c: &mut Criterion) {
    c.bench_function("placeholder", |b| b.iter(|| std::hint::black_box(2.0_f64).sqrt()));
}

criterion_group!(benches, kernels);
