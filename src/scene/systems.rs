//! The frame's systems, in schedule order: input, physics, extract.

use super::components::{
    Ball, CradleState, FlatScene, FrameImpacts, Light, Material, Pendulum, Quality, Shape,
    SimClock, SimState, Strand, StrandOf, SwingBox, Transform, View,
};
use super::spawn::{attach_point, ball_transform};
use crate::trace;
use bevy_ecs::prelude::*;
use glam::DVec3;

/// Balls as the string system reads them (disjoint from the strings it writes).
type BallsRead<'w, 's> = Query<
    'w,
    's,
    (&'static Pendulum, &'static Transform, &'static Shape),
    (With<Ball>, Without<Strand>),
>;

/// Everything the tracer draws, with whether it moves, and whether each part
/// changed since the last extract.
type Drawables<'w, 's> = Query<
    'w,
    's,
    (
        Ref<'static, Transform>,
        Ref<'static, Shape>,
        Ref<'static, Material>,
        Has<Ball>,
        Has<Strand>,
    ),
>;

/// Input: the clock runs only while running.
pub fn advance_clock(state: Res<SimState>, mut clock: ResMut<SimClock>) {
    if *state == SimState::Running {
        clock.t += clock.frame_dt;
    }
}

/// Physics: the cradle's state at the clock's time, or, past the frame's
/// deadline, at the latest time reached (the clock then waits there); the
/// impacts on the way are the frame's.
pub fn step_physics(
    mut clock: ResMut<SimClock>,
    mut sim: ResMut<CradleState>,
    mut impacts: ResMut<FrameImpacts>,
) {
    impacts.impacts.clear();
    impacts.courses.clear();
    if sim.snapshot.t != clock.t {
        let snapshot = match clock.deadline {
            Some(d) => sim.cradle.snapshot_by(clock.t, d),
            None => sim.cradle.snapshot(clock.t),
        };
        if snapshot.t < clock.t {
            clock.t = snapshot.t;
        }
        impacts.impacts = sim.cradle.take_impacts(snapshot.t);
        impacts.courses = sim.cradle.take_courses(snapshot.t);
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
    // Only a transform that moves is written, so that its change tick tells
    // the tracer what moved (a ball at rest keeps its pixels).
    for (p, mut t) in &mut balls {
        t.set_if_neq(ball_transform(
            p.pivot,
            p.length,
            sim.snapshot.theta[p.index],
        ));
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
        t.set_if_neq(Transform::segment(of.anchor, tops[of.ball]));
    }
}

/// The radius (m) a string needs to be `PIXELS_WIDE` wide at distance `d` (m)
/// from the camera of `scene`.
fn string_floor(scene: &trace::Scene, d: f64) -> f64 {
    /// A string is drawn at least this wide: thinner, the pixel centres miss
    /// it by turns as it swings, and it shimmers; anti-aliasing only finds
    /// edges the centre samples see.
    const PIXELS_WIDE: f64 = 1.0;
    let fov = f64::from(scene.camera.fov_deg).to_radians();
    let per_pixel = 2.0 * (0.5 * fov).tan() / f64::from(scene.size.1.max(1));
    0.5 * PIXELS_WIDE * per_pixel * d
}

/// Extract: the user's view and the render quality into the flat scene, when
/// they changed (then the tracer's next frame is full).
pub fn apply_view(view: Res<View>, quality: Res<Quality>, mut flat: ResMut<FlatScene>) {
    if view.is_changed() || quality.is_changed() {
        let flat = &mut *flat;
        flat.scene.camera = view.0;
        quality.set_on(&mut flat.scene);
        flat.change.merge(trace::Change::Any);
    }
}

/// Extract: copies each object's shape (from its transform) and material, and
/// the lights, into the flat scene; the rest of it was set at spawn. Strings
/// far from the camera are drawn [`string_floor`] thick, at least, and the
/// swing box the tracer gets is widened to hold them. What changed goes with
/// it: the moving objects whose transforms changed, or anything when a
/// static object, a shape, a material, a light or the swing box did.
pub fn extract(
    objects: Drawables,
    lights: Query<Ref<Light>>,
    swing: Res<SwingBox>,
    mut flat: ResMut<FlatScene>,
) {
    let FlatScene { scene, change } = &mut *flat;
    let same_count =
        scene.objects.len() == objects.iter().len() && scene.lights.len() == lights.iter().len();
    let mut now = if same_count && !swing.is_changed() && !lights.iter().any(|l| l.is_changed()) {
        trace::Change::none()
    } else {
        trace::Change::Any
    };
    scene.objects.clear();
    // Each string's floor is from its own far end; the swing box is widened
    // by the floor at its corner furthest from the eye, which no string's
    // exceeds, so the box stays the same while the view does.
    let eye = scene.camera.position.as_dvec3();
    let SwingBox(lo, hi) = *swing;
    let far = (0..8)
        .map(|i| {
            let pick = |bit: usize, l: f32, h: f32| f64::from(if i & bit == 0 { l } else { h });
            DVec3::new(
                pick(1, lo.x, hi.x),
                pick(2, lo.y, hi.y),
                pick(4, lo.z, hi.z),
            )
        })
        .map(|corner| (corner - eye).length())
        .fold(0.0, f64::max);
    let most = string_floor(scene, far);
    let mut widened = 0.0_f64;
    for (i, (t, shape, material, is_ball, is_strand)) in objects.iter().enumerate() {
        let moving = is_ball || is_strand;
        if shape.is_changed() || material.is_changed() || (t.is_changed() && !moving) {
            now = trace::Change::Any;
        } else if t.is_changed()
            && let trace::Change::Moved(list) = &mut now
        {
            list.push(i);
        }
        let shape = match *shape {
            Shape::Sphere { radius } => trace::Shape::Sphere {
                centre: t.translation.as_vec3(),
                radius: radius as f32,
            },
            Shape::Cylinder { radius, length } => {
                let half = t.rotation * DVec3::new(0.0, 0.5 * length, 0.0);
                let (a, b) = (t.translation - half, t.translation + half);
                let radius = if is_strand {
                    widened = widened.max(most - radius);
                    radius.max(string_floor(
                        scene,
                        (a - eye).length().max((b - eye).length()),
                    ))
                } else {
                    radius
                };
                trace::Shape::Cylinder {
                    a: a.as_vec3(),
                    b: b.as_vec3(),
                    radius: radius as f32,
                }
            }
            Shape::Plane => trace::Shape::Plane {
                point: t.translation.as_vec3(),
                normal: (t.rotation * DVec3::Y).as_vec3(),
            },
        };
        scene.objects.push(trace::Object {
            shape,
            material: material.0,
            moving,
        });
    }
    scene.lights.clear();
    scene.lights.extend(lights.iter().map(|l| l.0));
    change.merge(now);
    // The strings drawn thicker stay inside the box widened as much.
    let grow = glam::Vec3::splat(widened as f32 * 1.001);
    scene.motion_bounds = Some((lo - grow, hi + grow));
}
