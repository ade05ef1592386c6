//! Packets (eight pixels traced together in SIMD lanes) against the scalar
//! reference render (`RenderOptions::FULL`, serial), byte for byte: at several
//! thread counts, at picture sizes that are not multiples of the packet width,
//! and with rays that degenerate (parallel to the floor, grazing a ball's rim,
//! meeting a cylinder's cap edge-on).

use newtons_cradle::config::{Config, LightConfig};
use newtons_cradle::scene::CradleWorld;
use newtons_cradle::trace::{self, RenderOptions, Scene};

/// The scene of `config` at simulated time `t`.
/// The scene of `config` at time `t`, at one sample per pixel (packets trace the
/// centre samples; anti-aliased frames are tested in frames.rs).
fn scene_at(config: &Config, t: f64) -> Scene {
    let mut config = config.clone();
    config.render.samples = 1;
    let mut world = CradleWorld::new(&config);
    world.show_at(t);
    world.scene().clone()
}

/// Asserts that the packet renders (serial and at 1, 2, 3 and 7 threads) equal
/// the scalar reference.
fn assert_packets_match(s: &Scene, what: &str) {
    let reference = trace::render_serial_with(s, RenderOptions::FULL);
    assert!(trace::render_serial(s) == reference, "{what}: serial");
    for threads in [1, 2, 3, 7] {
        let pool = trace::pool(threads).expect("pool");
        let img = pool.install(|| trace::render(s));
        assert!(img == reference, "{what}: {threads} threads");
    }
}

#[test]
fn packets_equal_the_scalar_reference_at_any_thread_count_and_size() {
    // Widths below, at and off multiples of 8; heights odd.
    for (w, h) in [(16, 16), (17, 9), (61, 37), (203, 101), (240, 120)] {
        let mut config = Config::default();
        (config.render.width, config.render.height) = (w, h);
        config.start.lift = 2;
        assert_packets_match(&scene_at(&config, 0.37), &format!("{w}x{h}"));
    }
}

#[test]
fn the_portable_build_of_the_packets_equals_the_reference_too() {
    // This machine may pick AVX2: make it run the SSE2 build as well. Both builds
    // give the same bytes, so other tests running meanwhile are unaffected.
    trace::packet::force_portable(true);
    let mut config = Config::default();
    (config.render.width, config.render.height) = (61, 37);
    assert_packets_match(&scene_at(&config, 0.37), "portable build");
    trace::packet::force_portable(false);
}

#[test]
fn packets_equal_the_reference_for_rays_parallel_to_the_floor() {
    // The eye level with the horizon: the middle rows' rays run parallel to the
    // floor (a zero denominator), the ones just below meet it far away.
    for eye_y in [0.12, 1e-4, 0.0] {
        let mut config = Config::default();
        (config.render.width, config.render.height) = (96, 48);
        config.camera.position = [0.0, eye_y, 0.6];
        config.camera.look_at = [0.0, eye_y, 0.0];
        config.camera.fit = false;
        assert_packets_match(&scene_at(&config, 0.2), &format!("eye at y = {eye_y}"));
    }
}

#[test]
fn packets_equal_the_reference_at_grazing_rims_caps_and_light() {
    let mut base = Config::default();
    (base.render.width, base.render.height) = (96, 48);
    base.camera.fit = false;
    // Looking along the top rail: its caps face the eye and its body is seen
    // end-on; the posts' caps meet the rays edge-on.
    let mut along = base.clone();
    along.camera.position = [0.6, base.cradle.pivot_height, base.cradle.rail_spread];
    along.camera.look_at = [0.0, base.cradle.pivot_height, base.cradle.rail_spread];
    assert_packets_match(&scene_at(&along, 0.1), "along the rail");
    // A close-up of one ball: its rim grazes the rays of a ring of pixels.
    let mut close = base.clone();
    close.camera.position = [0.0, 0.09, 0.08];
    close.camera.look_at = [0.0, 0.09, 0.0];
    close.camera.fov_deg = 40.0;
    assert_packets_match(&scene_at(&close, 0.0), "a ball's rim");
    // Light grazing the floor: long shadows and lambert near 0 on the floor.
    let mut low = base;
    low.lights = vec![
        LightConfig::Ambient {
            color: [1.0, 1.0, 1.0],
            intensity: 0.1,
        },
        LightConfig::Directional {
            direction: [1.0, -0.02, 0.3],
            color: [1.0, 1.0, 1.0],
            intensity: 0.9,
        },
        LightConfig::Point {
            position: [-0.5, 0.02, 0.4],
            color: [1.0, 0.9, 0.8],
            intensity: 0.6,
        },
    ];
    assert_packets_match(&scene_at(&low, 0.3), "grazing light");
}

#[test]
fn every_mix_of_the_skips_equals_the_reference() {
    // Packets need tile culling; with shadow culling off their lanes on the
    // cradle test every object for shadows, with it on the casters' lists.
    let mut config = Config::default();
    (config.render.width, config.render.height) = (96, 48);
    config.start.lift = 2;
    let s = scene_at(&config, 0.37);
    let reference = trace::render_serial_with(&s, RenderOptions::FULL);
    for bits in 0..16 {
        let options = RenderOptions {
            tile_culling: bits & 1 != 0,
            shadow_culling: bits & 2 != 0,
            bvh: bits & 4 != 0,
            packets: bits & 8 != 0,
        };
        let img = trace::render_serial_with(&s, options);
        assert!(img == reference, "{options:?}");
    }
}

#[test]
fn packets_equal_the_reference_at_every_reflection_depth() {
    // No mirror rays at all, one bounce, and the most the config allows
    // (touching balls reflect each other many times over).
    for depth in [0, 1, 2, 16] {
        let mut config = Config::default();
        (config.render.width, config.render.height) = (96, 48);
        config.render.max_depth = depth;
        config.start.lift = 2;
        assert_packets_match(&scene_at(&config, 0.37), &format!("depth {depth}"));
    }
}
