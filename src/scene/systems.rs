//! The frame's systems, in schedule order: input, physics, extract.

use super::components::{
    Ball, CradleState, FlatScene, Light, Material, Pendulum, Shape, SimClock, SimState, Strand,
    StrandOf, Transform,
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

/// Extract: copies each object's shape (from its transform) and material, and
/// the lights, into the flat scene; the rest of it was set at spawn.
pub fn extract(objects: Drawables, lights: Query<&Light>, mut flat: ResMut<FlatScene>) {
    let scene = &mut flat.0;
    scene.objects.clear();
    for (t, shape, material, is_ball, is_strand) in &objects {
        let shape = match *shape {
            Shape::Sphere { radius } => trace::Shape::Sphere {
                centre: t.translation.as_vec3(),
                radius: radius as f32,
            },
            Shape::Cylinder { radius, length } => {
                let half = t.rotation * DVec3::new(0.0, 0.5 * length, 0.0);
                trace::Shape::Cylinder {
                    a: (t.translation - half).as_vec3(),
                    b: (t.translation + half).as_vec3(),
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
            moving: is_ball || is_strand,
        });
    }
    scene.lights.clear();
    scene.lights.extend(lights.iter().map(|l| l.0));
}
