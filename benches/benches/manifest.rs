//! The cost of a run directory's manifest (issue 27): hashing a file by size and XXH3-128
//! content (`flocking::owned::manifest::Digest::of_file`, what a run does once when it finishes
//! and `--force` does before replacing it), side by side with writing the same bytes, for a file
//! of a trajectory's size.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use flocking::owned::manifest::Digest;
use std::hint::black_box;

/// 256 MiB of trajectory-like CSV text.
const SIZE: usize = 256 << 20;

fn manifest(c: &mut Criterion) {
    let row = b"1234,-12.345678901234567,3.4567890123456789,0.123456789012345,-0.98765432109876\n";
    let bytes: Vec<u8> = row.iter().copied().cycle().take(SIZE).collect();
    let dir = tempfile::tempdir().expect("a temporary directory");
    let path = dir.path().join("trajectory.csv");
    std::fs::write(&path, &bytes).expect("written");
    let mut group = c.benchmark_group("manifest");
    group.throughput(Throughput::Bytes(SIZE as u64));
    group.bench_function("hash 256 MiB file", |b| {
        b.iter(|| black_box(Digest::of_file(&path).expect("hashed")));
    });
    group.bench_function("write 256 MiB file", |b| {
        b.iter(|| std::fs::write(&path, black_box(&bytes)).expect("written"));
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(std::time::Duration::from_millis(300))
        .measurement_time(std::time::Duration::from_secs(5));
    targets = manifest
}
criterion_main!(benches);
