//! One 1200x600 frame of the default scene, swinging, on every core; and the HUD
//! drawn over such a frame, to show it costs nothing next to the trace.

use criterion::{Criterion, criterion_group, criterion_main};
use newtons_cradle::app::hud::Canvas;
use newtons_cradle::app::session::Overlay;
use newtons_cradle::config::Config;
use newtons_cradle::scene::CradleWorld;
use newtons_cradle::trace;

fn frame(c: &mut Criterion) {
    let config = Config::default();
    let mut world = CradleWorld::new(&config);
    world.show_at(0.5);
    let scene = world.scene().clone();
    c.bench_function("render 1200x600 default scene", |b| {
        b.iter(|| trace::render(std::hint::black_box(&scene)));
    });
    // The skips against the reference, serially: their ratio is what they save.
    for (name, options) in [
        ("full", trace::RenderOptions::FULL),
        ("fast", trace::RenderOptions::FAST),
    ] {
        c.bench_function(&format!("render 1200x600 serial {name}"), |b| {
            b.iter(|| trace::render_serial_with(std::hint::black_box(&scene), options));
        });
    }
}

fn hud(c: &mut Criterion) {
    let mut rgba = vec![128u8; 1200 * 600 * 4];
    let status: Vec<(String, [u8; 3])> = [
        "RUNNING   fps   6.4   trace  146.4 ms   t     7.73 s   rate 1x",
        "balls 5   lifted 1 at 30.0 deg   ideal   energy err -1.3e-16",
        "H: help   TAB: panel",
    ]
    .iter()
    .map(|l| ((*l).to_string(), [235, 235, 235]))
    .collect();
    let overlay = Overlay {
        status,
        help: true,
        notices: vec![(
            "saved screenshot newtons-cradle-20261203-101010.png".into(),
            [150, 230, 160],
        )],
    };
    c.bench_function("hud status, help and a notice over 1200x600", |b| {
        b.iter(|| {
            let mut canvas = Canvas {
                rgba: &mut rgba,
                width: 1200,
                height: 600,
                bgra: false,
                scale: 2,
            };
            canvas.overlay(std::hint::black_box(&overlay))
        });
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = frame, hud
}
criterion_main!(benches);
