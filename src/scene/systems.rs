//! The frame's systems, in schedule order: input, physics, extract.

use super::components::{
    ActiveConfig, Ball, CameraRes, Control, CradleState, FlatScene, Light, Material, Pendulum,
    Shape, SimClock, SimState, Strand, StrandOf, Transform,
};
use super::spawn::{attach_point, ball_transform};
use crate::config::LightConfig;
use crate::trace;
use bevy_ecs::prelude::*;
use glam::{DVec3, Vec3};

/// Balls as the string system reads them (disjoint from the strings it writes).
type BallsRead<'w, 's> = Query<
    'w,
    's,
    (&'static Pendulum, &'static Transform, &'static Shape),
    (With<Ball>, Without<Strand>),
>;

/// Everything the tracer draws, with whether it moves.
type Drawables<'w, 's> = Query<
    'w,
    's,
    (
        &'static Transform,
        &'static Shape,
        &'static Material,
        Has<Ball>,
        Has<Strand>,
    ),
>;

/// Input: applies the user's controls (start/stop, reset).
pub fn apply_controls(
    mut controls: MessageReader<Control>,
    mut state: ResMut<SimState>,
    mut clock: ResMut<SimClock>,
    mut sim: ResMut<CradleState>,
    config: Res<ActiveConfig>,
) {
    for control in controls.read() {
        match control {
            Control::TogglePause => {
                *state = match *state {
                    SimState::Running => SimState::Paused,
                    SimState::Paused => SimState::Running,
                };
            }
            Control::Reset => {
                let c = &config.0;
                let mut cradle = c.build_cradle();
                let snapshot = cradle.snapshot(0.0);
                *sim = CradleState { cradle, snapshot };
                clock.t = 0.0;
                *state = if c.start.running {
                    SimState::Running
                } else {
                    SimState::Paused
                };
            }
        }
    }
}

/// Input: the clock runs only while running.
pub fn advance_clock(state: Res<SimState>, mut clock: ResMut<SimClock>) {
    if *state == SimState::Running {
        clock.t += clock.frame_dt;
    }
}

/// Physics: the cradle's state at the clock's time.
pub fn step_physics(clock: Res<SimClock>, mut sim: ResMut<CradleState>) {
    if sim.snapshot.t != clock.t {
        let snapshot = sim.cradle.snapshot(clock.t);
        sim.snapshot = snapshot;
    }
}

/// Physics: each ball hangs at its pendulum's angle.
pub fn place_balls(
    sim: Res<CradleState>,
    mut balls: Query<(&Pendulum, &mut Transform), With<Ball>>,
) {
    if !sim.is_changed() {
        return;
    }
    for (p, mut t) in &mut balls {
        *t = ball_transform(p.pivot, p.length, sim.snapshot.theta[p.index]);
    }
}

/// Physics: each string runs from its rail anchor to the top of its ball.
pub fn place_strands(
    sim: Res<CradleState>,
    balls: BallsRead,
    mut strands: Query<(&StrandOf, &mut Transform), With<Strand>>,
) {
    if !sim.is_changed() {
        return;
    }
    let mut tops = vec![DVec3::ZERO; balls.iter().len()];
    for (p, t, shape) in &balls {
        if let Shape::Sphere { radius } = shape {
            tops[p.index] = attach_point(t, *radius);
        }
    }
    for (of, mut t) in &mut strands {
        *t = Transform::segment(of.anchor, tops[of.ball]);
    }
}

fn v3(v: DVec3) -> Vec3 {
    v.as_vec3()
}

fn arr3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32)
}

/// A box holding every position balls and strings can take at any time.
///
/// Energy bounds the swing: the exact engine never adds energy (a tested property),
/// and no ball can hold more than all of it, so with `k` balls lifted to `A` no ball
/// passes `theta_max = 2 asin(sqrt(k) sin(A/2))` (exactly `A` for one ball).
/// Fixed-step integrators can gain energy, so for them any angle is allowed. Strings
/// run from the rails (at `+-rail_spread`, height `pivot_height`) to the balls.
fn motion_bounds(config: &crate::config::Config) -> (Vec3, Vec3) {
    let layout = super::spawn::Layout::new(config);
    let c = &config.cradle;
    let theta_max = if config.physics.integrator == crate::physics::Integrator::Exact {
        let s = (config.start.lift as f64).sqrt() * (0.5 * config.lift_angle()).sin();
        2.0 * s.min(1.0).asin()
    } else {
        std::f64::consts::PI
    };
    let side = c.length * theta_max.min(std::f64::consts::FRAC_PI_2).sin();
    let reach = c.radius + c.string_radius;
    let (first, last) = (layout.pivot(0), layout.pivot(c.balls - 1));
    let top = (first.y - c.length * theta_max.cos()).max(first.y);
    let z = c.rail_spread + c.string_radius;
    let lo = DVec3::new(first.x - side - reach, first.y - c.length - reach, -z);
    let hi = DVec3::new(last.x + side + reach, top + reach, z);
    // f32 rounding of the corners must not shrink the box: widen by a micrometre.
    (v3(lo) - Vec3::splat(1e-6), v3(hi) + Vec3::splat(1e-6))
}

/// Extract: gathers shapes, materials, lights and camera into the flat scene.
pub fn extract(
    objects: Drawables,
    lights: Query<&Light>,
    camera: Res<CameraRes>,
    config: Res<ActiveConfig>,
    mut flat: ResMut<FlatScene>,
) {
    let scene = &mut flat.0;
    scene.objects.clear();
    for (t, shape, material, is_ball, is_strand) in &objects {
        let shape = match *shape {
            Shape::Sphere { radius } => trace::Shape::Sphere {
                centre: v3(t.translation),
                radius: radius as f32,
            },
            Shape::Cylinder { radius, length } => {
                let half = t.rotation * DVec3::new(0.0, 0.5 * length, 0.0);
                trace::Shape::Cylinder {
                    a: v3(t.translation - half),
                    b: v3(t.translation + half),
                    radius: radius as f32,
                }
            }
            Shape::Plane => trace::Shape::Plane {
                point: v3(t.translation),
                normal: v3(t.rotation * DVec3::Y),
            },
        };
        scene.objects.push(trace::Object {
            shape,
            material: material.0,
            moving: is_ball || is_strand,
        });
    }
    scene.lights.clear();
    scene.lights.extend(lights.iter().map(|l| match &l.0 {
        LightConfig::Ambient { color, intensity } => trace::Light::Ambient {
            color: arr3(*color) * *intensity as f32,
        },
        LightConfig::Point {
            position,
            color,
            intensity,
        } => trace::Light::Point {
            position: arr3(*position),
            color: arr3(*color) * *intensity as f32,
        },
        LightConfig::Directional {
            direction,
            color,
            intensity,
        } => trace::Light::Directional {
            direction: arr3(*direction).normalize(),
            color: arr3(*color) * *intensity as f32,
        },
    }));
    let cam = &camera.0;
    scene.camera = trace::Camera {
        position: arr3(cam.position),
        look_at: arr3(cam.look_at),
        fov_deg: cam.fov_deg as f32,
    };
    let r = &config.0.render;
    scene.background = arr3(r.background);
    scene.size = (r.width, r.height);
    scene.max_depth = r.max_depth;
    scene.samples = r.samples;
    scene.adaptive = r.adaptive.then_some(r.adaptive_threshold as f32);
    scene.motion_bounds = Some(motion_bounds(&config.0));
}
