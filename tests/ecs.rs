//! The ECS world run headless: spawning, pause and run, strings that stay attached,
//! and the flat scene the extract stage fills.

use bevy_ecs::prelude::*;
use glam::DVec3;
use newtons_cradle::config::Config;
use newtons_cradle::scene::components::{Ball, Pendulum, Rod, Shape, Strand, StrandOf, Transform};
use newtons_cradle::scene::{CradleWorld, SimState};
use newtons_cradle::trace;

fn transforms<F: bevy_ecs::query::QueryFilter>(w: &mut CradleWorld) -> Vec<Transform> {
    w.world
        .query_filtered::<&Transform, F>()
        .iter(&w.world)
        .copied()
        .collect()
}

/// Both ends of a string cylinder, from its transform and length.
fn ends(t: &Transform, length: f64) -> (DVec3, DVec3) {
    let half = t.rotation * DVec3::new(0.0, 0.5 * length, 0.0);
    (t.translation - half, t.translation + half)
}

#[test]
fn spawns_balls_two_strings_each_rods_floor_and_lights() {
    let mut config = Config::default();
    config.cradle.balls = 7;
    let mut w = CradleWorld::new(&config);
    assert_eq!(transforms::<With<Ball>>(&mut w).len(), 7);
    assert_eq!(transforms::<With<Strand>>(&mut w).len(), 14);
    assert!(
        transforms::<With<Rod>>(&mut w).len() >= 4,
        "rails and posts"
    );
    w.frame(0.0);
    let scene = w.scene();
    let spheres = scene
        .objects
        .iter()
        .filter(|o| matches!(o.shape, trace::Shape::Sphere { .. }))
        .count();
    let planes = scene
        .objects
        .iter()
        .filter(|o| matches!(o.shape, trace::Shape::Plane { .. }))
        .count();
    assert_eq!((spheres, planes), (7, 1));
    assert_eq!(
        scene.objects.iter().filter(|o| o.moving).count(),
        7 + 14,
        "balls and strings move"
    );
    assert_eq!(scene.lights.len(), config.lights.len());
    assert_eq!(scene.size, (1200, 600));
}

#[test]
fn paused_world_does_not_move() {
    let config = Config::default();
    assert!(!config.start.running, "the default starts held up");
    let mut w = CradleWorld::new(&config);
    w.frame(0.0);
    let before = transforms::<With<Ball>>(&mut w);
    for _ in 0..120 {
        w.frame(1.0 / 60.0);
    }
    assert_eq!(w.state(), SimState::Paused);
    assert_eq!(transforms::<With<Ball>>(&mut w), before);
    assert_eq!(w.cradle().snapshot.t, 0.0);
}

#[test]
fn running_world_moves_balls_and_keeps_strings_attached() {
    let mut config = Config::default();
    config.start.lift = 2;
    config.start.angle_deg = 60.0;
    config.cradle.gap = 0.002;
    let mut w = CradleWorld::new(&config);
    w.set_running(true);
    w.frame(0.0);
    let start = transforms::<With<Ball>>(&mut w);
    let radius = config.cradle.radius;
    let want_len =
        ((config.cradle.length - radius).powi(2) + config.cradle.rail_spread.powi(2)).sqrt();
    let mut moved = false;
    for _ in 0..240 {
        w.frame(1.0 / 60.0);
        moved |= transforms::<With<Ball>>(&mut w) != start;
        let balls: Vec<(Pendulum, Transform)> = w
            .world
            .query::<(&Pendulum, &Transform)>()
            .iter(&w.world)
            .map(|(p, t)| (*p, *t))
            .collect();
        let mut strands = w
            .world
            .query_filtered::<(&StrandOf, &Transform, &Shape), With<Strand>>();
        for (of, t, shape) in strands.iter(&w.world) {
            let Shape::Cylinder { length, .. } = *shape else {
                panic!("strings are cylinders")
            };
            let (rail_end, ball_end) = ends(t, length);
            let (_, ball) = balls
                .iter()
                .find(|(p, _)| p.index == of.ball)
                .expect("each string has its ball");
            let top = ball.translation + ball.rotation * DVec3::new(0.0, radius, 0.0);
            // Ends are rebuilt from the physics each frame in f64: round-off of a
            // few ulps of 0.3 m, far below the promised 1e-12 m.
            assert!(
                (rail_end - of.anchor).length() < 1e-12,
                "rail end off by {:e}",
                (rail_end - of.anchor).length()
            );
            assert!(
                (ball_end - top).length() < 1e-12,
                "ball end off by {:e}",
                (ball_end - top).length()
            );
            assert!(
                (length - want_len).abs() < 1e-12
                    && ((ball_end - rail_end).length() - want_len).abs() < 1e-12
            );
        }
    }
    assert!(moved, "balls moved while running");
    assert!(w.cradle().snapshot.collisions > 0);
}

#[test]
fn reset_returns_to_the_start_and_pause_stops_the_clock() {
    let mut config = Config::default();
    config.start.running = true;
    let mut w = CradleWorld::new(&config);
    w.frame(0.0);
    let start = transforms::<With<Ball>>(&mut w);
    for _ in 0..30 {
        w.frame(1.0 / 60.0);
    }
    assert_ne!(transforms::<With<Ball>>(&mut w), start);
    w.set_running(false);
    w.frame(1.0 / 60.0);
    assert_eq!(w.state(), SimState::Paused);
    let paused = transforms::<With<Ball>>(&mut w);
    w.frame(1.0 / 60.0);
    assert_eq!(transforms::<With<Ball>>(&mut w), paused);
    w.respawn(&config);
    w.frame(1.0 / 60.0);
    assert_eq!(
        w.state(),
        SimState::Running,
        "reset restores the asset's running flag"
    );
    assert_eq!(
        w.cradle().snapshot.t,
        1.0 / 60.0,
        "reset to 0, then one frame"
    );
}

#[test]
fn frame_stays_clear_of_the_swing() {
    // Posts stand beyond the farthest reach of any ball, for any lift angle.
    for angle in [10.0, 45.0, 90.0, 170.0] {
        let mut config = Config::default();
        config.start.angle_deg = angle;
        let layout = newtons_cradle::scene::layout::Layout::new(&config);
        let last = layout.pivot(config.cradle.balls - 1).x;
        let reach =
            config.cradle.length * f64::to_radians(angle.min(90.0)).sin() + config.cradle.radius;
        assert!(
            layout.half_width - config.cradle.frame_radius > last + reach,
            "angle {angle}"
        );
    }
}

#[test]
fn far_strings_are_drawn_a_pixel_wide_inside_the_widened_swing_box() {
    // A string thinner than a pixel is missed by the pixel centres by turns as
    // it swings, and shimmers: far ones are drawn at least one pixel wide.
    let pixel_at = |scene: &trace::Scene, d: f64| {
        let fov = f64::from(scene.camera.fov_deg).to_radians();
        2.0 * (0.5 * fov).tan() / f64::from(scene.size.1) * d
    };
    let strings = |scene: &trace::Scene| -> Vec<(glam::Vec3, glam::Vec3, f32)> {
        scene
            .objects
            .iter()
            .filter(|o| o.moving)
            .filter_map(|o| match o.shape {
                trace::Shape::Cylinder { a, b, radius } => Some((a, b, radius)),
                _ => None,
            })
            .collect()
    };
    let mut config = Config::default();
    config.cradle.balls = 200;
    config.start.lift = 20;
    let mut w = CradleWorld::new(&config);
    w.show_at(0.3);
    let scene = w.scene();
    let eye = scene.camera.position.as_dvec3();
    let (lo, hi) = scene.motion_bounds.expect("a swing box");
    let found = strings(scene);
    assert_eq!(found.len(), 400);
    let mut widened = 0;
    for (a, b, r) in found {
        let far = (a.as_dvec3() - eye)
            .length()
            .max((b.as_dvec3() - eye).length());
        // f32 radius against the f64 floor: a relative 1e-6 of rounding.
        assert!(
            f64::from(r) >= 0.5 * pixel_at(scene, far) * (1.0 - 1e-6),
            "a string {far:.2} m away is {r} m thick"
        );
        assert!(f64::from(r) >= config.cradle.string_radius * (1.0 - 1e-6));
        widened += usize::from(f64::from(r) > config.cradle.string_radius * 1.001);
        let r = glam::Vec3::splat(r);
        for end in [a, b] {
            assert!(
                (end - r).cmpge(lo).all() && (end + r).cmple(hi).all(),
                "every string stays inside the motion bounds"
            );
        }
    }
    assert!(widened > 100, "the far strings are widened: {widened}");
    // The default view's strings are wider than a pixel already: unchanged.
    let mut w = CradleWorld::new(&Config::default());
    w.show_at(0.0);
    let near = strings(w.scene());
    assert!(
        near.iter()
            .all(|&(_, _, r)| f64::from(r) == f64::from(0.0006_f32)),
        "{near:?}"
    );
}

/// The ECS tells the tracer what changed: exactly the moving objects whose
/// shapes changed since it last took the change (what comparing the two
/// flat scenes finds), nothing while paused, and anything after a respawn or
/// an edit of the view or the quality.
#[test]
fn the_change_the_ecs_hands_the_tracer_is_what_moved() {
    use trace::Change;
    let mut config = Config::default();
    config.start.running = true;
    let mut w = CradleWorld::new(&config);
    w.frame(0.0);
    assert_eq!(w.take_change(), Change::Any, "the first frame is new");
    let mut last = w.scene().clone();
    let mut moved_some = 0;
    for n in 0..240 {
        // Frames taken one at a time, and now and then two before a take:
        // the change covers every frame since the last take.
        w.frame(1.0 / 60.0);
        if n % 7 == 3 {
            w.frame(1.0 / 60.0);
        }
        let change = w.take_change();
        assert_eq!(change, Change::between(&last, w.scene()), "frame {n}");
        if let Change::Moved(list) = &change {
            // A swing of one lifted ball: the balls at rest keep their shapes.
            assert!(
                list.len() < w.scene().objects.len() / 2,
                "frame {n}: {list:?}"
            );
            moved_some += usize::from(!list.is_empty());
        }
        last = w.scene().clone();
    }
    assert!(moved_some > 200, "the swing moved things: {moved_some}");

    w.set_running(false);
    w.frame(1.0 / 60.0);
    let _ = w.take_change();
    for _ in 0..10 {
        w.frame(1.0 / 60.0);
        assert_eq!(w.take_change(), Change::none(), "paused: nothing moves");
    }
    let camera = w.scene().camera;
    w.set_camera(camera);
    w.frame(0.0);
    assert_eq!(
        w.take_change(),
        Change::none(),
        "the same view is no change"
    );
    let mut turned = camera;
    turned.position.x += 0.01;
    w.set_camera(turned);
    w.frame(0.0);
    assert_eq!(w.take_change(), Change::Any, "a new view");
    assert_eq!(w.scene().camera, turned);
    w.set_quality(newtons_cradle::scene::components::Quality {
        samples: 1,
        adaptive: None,
        coarse: 2,
    });
    w.frame(0.0);
    assert_eq!(w.take_change(), Change::Any, "a new quality");
    let s = w.scene();
    assert_eq!((s.samples, s.adaptive, s.coarse), (1, None, 2));
    w.respawn(&config);
    w.frame(0.0);
    assert_eq!(w.take_change(), Change::Any, "a respawned world");
}
