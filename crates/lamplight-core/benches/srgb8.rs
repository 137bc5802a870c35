//! 8-bit sRGB encoding of a 1280x720 image's channels: [`Srgb8::encode_all`]
//! (eight values a step with AVX2) against [`Srgb8::encode`] value by value.
//! The values spread over `[0, 1.3]`, so some clamp to white.
//!
//! `cargo bench -p lamplight-core --bench srgb8`

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use lamplight_core::film::Srgb8;

fn values() -> Vec<f32> {
    let mut state = 12345u64;
    (0..1280 * 720 * 3)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32 * 1.3
        })
        .collect()
}

fn srgb8(c: &mut Criterion) {
    let quantizer = Srgb8::get();
    let values = values();
    let mut out = vec![0u8; values.len()];
    let mut group = c.benchmark_group("srgb8_1280x720");
    group.throughput(Throughput::Elements(values.len() as u64));
    group.bench_function("encode_all", |b| b.iter(|| quantizer.encode_all(black_box(&values), &mut out)));
    group.bench_function("encode_each_value", |b| {
        b.iter(|| {
            for (o, &x) in out.iter_mut().zip(black_box(&values)) {
                *o = quantizer.encode(x);
            }
        })
    });
    group.finish();
}

criterion_group!(benches, srgb8);
criterion_main!(benches);
