//! One 1200x600 frame of the default scene, swinging, on every core.

use criterion::{Criterion, criterion_group, criterion_main};
use newtons_cradle::config::Config;
use newtons_cradle::scene::CradleWorld;
use newtons_cradle::trace;

fn frame(c: &mut Criterion) {
    let config = Config::default();
    let mut world = CradleWorld::new(&config);
    world.show_at(0.5);
    let scene = world.scene().clone();
    c.bench_function("render 1200x600 default scene", |b| {
        b.iter(|| trace::render(std::hint::black_box(&scene)))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = frame
}
criterion_main!(benches);
