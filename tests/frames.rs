//! Whole frames of the cradle: the parallel, culled, incremental and
//! anti-aliased renders against the serial reference, byte for byte; the sRGB
//! table. (The view's framing is tested in `view.rs`.)

use glam::Vec3;
use newtons_cradle::config::{Config, load_file};
use newtons_cradle::scene::CradleWorld;
use newtons_cradle::trace::{self, Light, Scene};

fn cradle_scene(width: u32, height: u32, t: f64) -> Scene {
    let mut config = Config::default();
    config.render.width = width;
    config.render.height = height;
    config.start.lift = 2;
    let mut world = CradleWorld::new(&config);
    world.show_at(t);
    world.scene().clone()
}

#[test]
fn parallel_render_equals_serial_byte_for_byte() {
    let s = cradle_scene(240, 120, 0.37);
    let serial = trace::render_serial(&s);
    for threads in [1, 2, 3, 7] {
        let pool = trace::pool(threads).expect("pool");
        let parallel = pool.install(|| trace::render(&s));
        assert!(
            parallel == serial,
            "{threads} threads differ from the serial render"
        );
    }
}

#[test]
fn srgb_bytes_round_the_standard_curve_to_nearest() {
    use newtons_cradle::trace::srgb8;
    // Against the IEC 61966-2-1 formula evaluated in f64, away from the decision
    // points (a value within 1e-6 of one may round either way in f32).
    for i in 0..=10_000 {
        let x = f64::from(i) / 10_000.0;
        let s = if x <= 0.003_130_8 {
            12.92 * x
        } else {
            1.055 * x.powf(1.0 / 2.4) - 0.055
        };
        let exact = s * 255.0;
        if (exact - exact.floor() - 0.5).abs() < 1e-3 {
            continue;
        }
        assert_eq!(srgb8(x as f32), exact.round() as u8, "linear {x}");
    }
    assert_eq!(
        (
            srgb8(-1.0),
            srgb8(0.0),
            srgb8(1.0),
            srgb8(7.0),
            srgb8(f32::NAN)
        ),
        (0, 0, 255, 255, 0)
    );
}

/// A default cradle at a small picture size with the given balls, lift and gap.
/// A small cradle traced at one sample per pixel (tests of anti-aliasing set it).
fn small_cradle(size: (u32, u32), balls: usize, lift: usize, gap: f64) -> Config {
    let mut config = Config::default();
    (config.render.width, config.render.height) = size;
    config.render.samples = 1;
    config.cradle.balls = balls;
    config.cradle.gap = gap;
    config.start.lift = lift;
    config
}

#[test]
fn tile_culling_and_the_bvh_leave_every_byte_as_the_full_render_makes_it() {
    use newtons_cradle::trace::{RenderOptions, render_serial_with};
    // Swinging cradles of several sizes and lifts, at times spread over a swing,
    // and a camera close enough that shapes reach past the picture's edges.
    for (balls, lift, gap, t) in [
        (5, 1, 0.0, 0.0),
        (5, 2, 0.0, 0.37),
        (9, 3, 0.002, 0.8),
        (20, 3, 0.001, 1.3),
        (60, 5, 0.0, 0.6),
        (200, 12, 0.0, 0.9),
    ] {
        let mut world = CradleWorld::new(&small_cradle((300, 150), balls, lift, gap));
        world.show_at(t);
        let mut s = world.scene().clone();
        let full = render_serial_with(&s, RenderOptions::FULL);
        assert!(
            render_serial_with(&s, RenderOptions::FAST) == full,
            "{balls} balls at t = {t}"
        );
        s.camera.position = Vec3::new(0.05, 0.16, 0.12);
        let full = render_serial_with(&s, RenderOptions::FULL);
        assert!(
            render_serial_with(&s, RenderOptions::FAST) == full,
            "{balls} balls at t = {t}, close up"
        );
    }
}

/// Renders 300 frames (5 s at 60 fps) of `config`'s swing incrementally and
/// asserts each equals the full reference render byte for byte, only the first
/// being traced in full; and that a copy kept up to date from each frame's
/// `changes` alone (as the window's framebuffer is) equals it too. Returns the
/// last frame's share of re-traced pixels and the mean share of the pixels the
/// frames after the first name as changed.
fn incremental_swing_equals_full(config: &Config, what: &str) -> (f64, f64) {
    use newtons_cradle::trace::{Incremental, RenderOptions, render_serial_with};
    let mut world = CradleWorld::new(config);
    let mut inc = Incremental::new();
    let (mut copy, mut copied) = (Vec::new(), None);
    let mut named = 0.0;
    for n in 0..300 {
        world.show_at(f64::from(n) / 60.0);
        // What moved, as the ECS says (the window's and sequences' way).
        let change = world.take_change();
        let scene = world.scene();
        let full = render_serial_with(scene, RenderOptions::FULL);
        let frame = inc.render_changed(scene, &change).clone();
        assert!(frame == full, "{what}: frame {n} differs");
        assert_eq!(
            inc.last_was_full(),
            n == 0,
            "{what}: only the first frame is traced in full"
        );
        let changes = inc.changes().expect("a frame was rendered");
        assert_ne!(
            Some(changes.id),
            copied,
            "{what}: frame {n} has a new number"
        );
        assert_eq!(changes.since.is_none(), n == 0, "{what}: frame {n}");
        if changes.since.is_some() && changes.since == copied {
            let stride = frame.width as usize * 4;
            let mut pixels = 0;
            for (y, &[a, b]) in changes.rows.iter().enumerate() {
                let span = y * stride + a as usize * 4..y * stride + b as usize * 4;
                copy[span.clone()].copy_from_slice(&frame.rgba[span]);
                pixels += b - a;
            }
            named += f64::from(pixels) / f64::from(frame.width * frame.height) / 299.0;
        } else {
            copy.clone_from(&frame.rgba);
        }
        copied = Some(changes.id);
        assert!(
            copy == frame.rgba,
            "{what}: frame {n}'s changes miss a byte"
        );
    }
    (inc.dynamic_share(), named)
}

#[test]
fn incremental_frames_equal_full_renders_over_300_frames_of_a_swing() {
    // 40 balls, 15 lifted: more pendulums than hit bits, so the 16th shares
    // the 15th's bit while they swing apart (the old places decide).
    let cases = [
        (5, 1, 0.0),
        (5, 2, 0.0),
        (20, 3, 0.0),
        (5, 1, 0.002),
        (40, 15, 0.0),
    ];
    for (balls, lift, gap) in cases {
        let config = small_cradle((160, 80), balls, lift, gap);
        let (share, _) = incremental_swing_equals_full(
            &config,
            &format!("{balls} balls, {lift} lifted, gap {gap}"),
        );
        assert!(
            share > 0.0 && share < 0.9,
            "{balls} balls: re-traces {share:.2} of the pixels"
        );
    }
}

#[test]
fn incremental_frames_equal_full_renders_where_shadows_reach_behind_the_eye() {
    // Along a long row from its left end: the blue light throws the left
    // strings' shadows back past the eye, so the screen's runs hold only what
    // of them lies in front.
    let mut config = small_cradle((160, 80), 50, 1, 0.0);
    config.camera.position = [-1.372, 0.3, 0.5];
    config.camera.look_at = [-0.548, 0.09, -0.026];
    config.camera.fit = false;
    let (share, _) = incremental_swing_equals_full(&config, "50 balls from the row's end");
    assert!(share > 0.0 && share < 0.5, "re-traces {share:.2}");
}

#[test]
fn anti_aliased_incremental_frames_equal_full_renders_over_300_frames() {
    // Adaptive anti-aliasing: an edge depends on the neighbours' colours, so a
    // frame re-tests the edges around every changed pixel and supersamples again
    // the edges whose samples' rays come near a moved object.
    for (balls, lift, samples, threshold) in [(5, 1, 4, 0.05), (5, 2, 16, 0.02), (20, 3, 4, 0.1)] {
        let mut config = small_cradle((160, 80), balls, lift, 0.0);
        config.render.samples = samples;
        config.render.adaptive = true;
        config.render.adaptive_threshold = threshold;
        let (share, named) =
            incremental_swing_equals_full(&config, &format!("{balls} balls, {samples} samples"));
        assert!(
            share > 0.0 && share < 0.5,
            "{balls} balls: re-traces {share:.2}"
        );
        // The changes name a part of the picture, each row's from its first
        // changed pixel to its last (wider than the pixels traced again).
        assert!(
            named > share && named < 0.6,
            "{balls} balls: names {named:.2} of the pixels as changed"
        );
    }
}

#[test]
fn the_realistic_cradles_incremental_frames_equal_full_renders() {
    // Soft Hertz contact and drag: after the first impact every ball moves
    // every frame, each ball's edges and mirror images with it.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/presets/realistic.ron");
    let mut config = load_file(std::path::Path::new(path)).expect("the preset loads");
    (config.render.width, config.render.height) = (160, 80);
    let (share, _) = incremental_swing_equals_full(&config, "the realistic cradle");
    assert!(share > 0.0 && share < 0.5, "re-traces {share:.2}");
}

#[test]
fn incremental_renders_in_full_when_anything_static_changes() {
    use newtons_cradle::trace::Incremental;
    let mut world = CradleWorld::new(&Config::default());
    world.show_at(0.2);
    let mut s = world.scene().clone();
    let mut inc = Incremental::new();
    let _ = inc.render(&s);
    let _ = inc.render(&s);
    assert!(!inc.last_was_full());
    s.camera.fov_deg += 1.0;
    let _ = inc.render(&s);
    assert!(inc.last_was_full(), "a new camera");
    s.lights.pop();
    let _ = inc.render(&s);
    assert!(inc.last_was_full(), "a light less");
    s.motion_bounds = None;
    let _ = inc.render(&s);
    let _ = inc.render(&s);
    assert!(inc.last_was_full(), "no motion box: nothing can be reused");
}

/// PSNR (dB) of `img` against `reference`, over the RGB bytes.
fn psnr(img: &trace::Image, reference: &trace::Image) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0);
    for (i, (a, b)) in img.rgba.iter().zip(&reference.rgba).enumerate() {
        if i % 4 != 3 {
            let d = f64::from(*a) - f64::from(*b);
            sum += d * d;
            n += 1.0;
        }
    }
    10.0 * (255.0 * 255.0 / (sum / n)).log10()
}

#[test]
fn adaptive_anti_aliasing_supersamples_exactly_the_edges() {
    let mut s = cradle_scene(240, 120, 0.4);
    s.adaptive = None;
    s.samples = 8;
    let uniform = trace::render_serial(&s);
    s.samples = 1;
    let single = trace::render_serial(&s);
    s.samples = 8;
    s.adaptive = Some(0.05);
    let adaptive = trace::render_serial(&s);
    // Edge pixels (in the one-sample picture) carry the 8-sample colour, the
    // others the one-sample colour, byte for byte.
    let (w, h) = (240usize, 120usize);
    let px = |img: &trace::Image, x: usize, y: usize| {
        img.rgba[(y * w + x) * 4..(y * w + x) * 4 + 3].to_vec()
    };
    let mut edges = 0;
    for y in 0..h {
        for x in 0..w {
            let here = px(&single, x, y);
            let near = [
                (x.wrapping_sub(1), y),
                (x + 1, y),
                (x, y.wrapping_sub(1)),
                (x, y + 1),
            ];
            let edge = near
                .iter()
                .filter(|(nx, ny)| *nx < w && *ny < h)
                .any(|&(nx, ny)| {
                    here.iter()
                        .zip(px(&single, nx, ny))
                        .any(|(a, b)| f32::from(a.abs_diff(b)) > 0.05 * 255.0)
                });
            let want = if edge { px(&uniform, x, y) } else { here };
            assert_eq!(px(&adaptive, x, y), want, "pixel ({x}, {y}), edge {edge}");
            edges += usize::from(edge);
        }
    }
    // A cradle has edges, but they are a minority of the picture.
    assert!(edges > 100 && edges < w * h / 2, "{edges} edge pixels");
    // And it is closer to a 16-sample reference than one sample is.
    s.adaptive = None;
    s.samples = 16;
    let reference = trace::render_serial(&s);
    assert!(psnr(&adaptive, &reference) > psnr(&single, &reference) + 3.0);
}

#[test]
fn adaptive_parallel_and_incremental_equal_serial() {
    let config = {
        let mut c = small_cradle((160, 80), 5, 1, 0.0);
        c.render.samples = 4;
        c.render.adaptive = true;
        c
    };
    let mut world = CradleWorld::new(&config);
    world.set_running(true);
    let mut inc = trace::Incremental::new();
    for threads in [1u32, 2, 3] {
        let pool = trace::pool(threads as usize).unwrap();
        for f in 0..4 {
            world.show_at(0.3 + f64::from(f) / 30.0 + f64::from(threads));
            let serial = trace::render_serial_with(world.scene(), trace::RenderOptions::FULL);
            assert_eq!(pool.install(|| trace::render(world.scene())), serial);
            assert_eq!(pool.install(|| inc.render(world.scene()).clone()), serial);
        }
    }
}

#[test]
fn shadow_culling_leaves_every_byte_as_the_full_render_makes_it() {
    use newtons_cradle::trace::{RenderOptions, render_serial_with};
    // Lights high and low (one below the rails, so the frame's shadow reaches
    // every point of the floor), beside the cradle, straight above, and
    // directional; each picture equals the reference with every shadow ray
    // testing every object.
    let mut world = CradleWorld::new(&small_cradle((240, 120), 7, 2, 0.0));
    world.show_at(0.45);
    let base = world.scene().clone();
    let white = Vec3::splat(0.6);
    let lights = [
        vec![Light::Point {
            position: Vec3::new(-0.6, 0.9, 0.8),
            color: white,
        }],
        vec![Light::Point {
            position: Vec3::new(0.3, 0.2, 0.1),
            color: white,
        }],
        vec![Light::Point {
            position: Vec3::new(0.0, 2.0, 0.0),
            color: white,
        }],
        vec![Light::Point {
            position: Vec3::new(1.5, 0.05, -0.4),
            color: white,
        }],
        vec![
            Light::Directional {
                direction: Vec3::new(0.3, -1.0, -0.2).normalize(),
                color: white,
            },
            Light::Ambient {
                color: Vec3::splat(0.1),
            },
        ],
    ];
    for set in lights {
        let s = Scene {
            lights: set.clone(),
            ..base.clone()
        };
        assert!(
            render_serial_with(&s, RenderOptions::FAST)
                == render_serial_with(&s, RenderOptions::FULL),
            "lights {set:?}"
        );
    }
}
