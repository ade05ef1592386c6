//! Spawning the world from a config: balls on V strings from two top rails, the
//! frame's rods, the floor and lights, plus the physics resources and the flat
//! scene's static part (`view`).

use super::components::{
    Ball, CradleState, FlatScene, Floor, FrameImpacts, Light, Material, Pendulum, Quality, Rod,
    Shape, SimClock, SimState, Strand, StrandOf, SwingBox, Transform, View,
};
use super::fit::static_scene;
use super::layout::Layout;
use super::view::{self, f32x3};
use crate::config::{Config, MaterialConfig};
use crate::trace;
use bevy_ecs::prelude::*;
use glam::DVec3;

/// Converts a config material to the tracer's.
#[must_use]
pub fn material(m: &MaterialConfig) -> Material {
    Material(trace::Material {
        color: f32x3(m.color),
        specular: m.specular.map(|e| e as f32),
        reflective: m.reflective as f32,
        checker: m.checker.map(|c| (f32x3(c), m.checker_size as f32)),
    })
}

/// Where a ball hangs at angle `theta`: centre and orientation.
#[must_use]
pub fn ball_transform(pivot: DVec3, length: f64, theta: f64) -> Transform {
    let (s, c) = theta.sin_cos();
    Transform {
        translation: pivot + DVec3::new(length * s, -length * c, 0.0),
        rotation: glam::DQuat::from_rotation_z(theta),
    }
}

/// The point on top of a ball where its strings meet (towards the swing axis).
#[must_use]
pub fn attach_point(ball: &Transform, radius: f64) -> DVec3 {
    ball.translation + ball.rotation * DVec3::new(0.0, radius, 0.0)
}

/// A world with every entity and resource for `config`, the cradle at t = 0.
#[must_use]
pub fn build_world(config: &Config) -> World {
    let mut world = World::new();
    spawn_entities(&mut world, config);
    insert_resources(&mut world, config);
    // Kept across respawns: the graphs stay open, their record starts again.
    world.insert_resource(super::record::Recording::default());
    world
}

/// Replaces every entity and resource by those of `config` (a new ball count, a
/// reloaded asset).
pub fn respawn(world: &mut World, config: &Config) {
    let old: Vec<Entity> = world
        .query_filtered::<Entity, Or<(With<Transform>, With<Light>)>>()
        .iter(world)
        .collect();
    for e in old {
        world.despawn(e);
    }
    spawn_entities(world, config);
    insert_resources(world, config);
}

fn insert_resources(world: &mut World, config: &Config) {
    world.insert_resource(CradleState::new(config.build_cradle()));
    world.insert_resource(FrameImpacts {
        origin: Layout::new(config).first_pivot,
        ..FrameImpacts::default()
    });
    world.insert_resource(SimClock::default());
    world.insert_resource(if config.start.running {
        SimState::Running
    } else {
        SimState::Paused
    });
    // Camera, lights and render settings are the tracer's types from here on.
    let scene = static_scene(config);
    world.insert_resource(View(scene.camera));
    world.insert_resource(Quality {
        samples: scene.samples,
        adaptive: scene.adaptive,
        coarse: scene.coarse,
    });
    world.insert_resource(FlatScene {
        scene,
        change: trace::Change::Any,
    });
    let (lo, hi) = view::motion_bounds(config);
    world.insert_resource(SwingBox(lo, hi));
}

fn spawn_entities(world: &mut World, config: &Config) {
    let c = &config.cradle;
    let m = &config.materials;
    let layout = Layout::new(config);
    let (ball_mat, string_mat, frame_mat) =
        (material(&m.ball), material(&m.string), material(&m.frame));
    let (theta, _) =
        crate::physics::params::lifted_start(c.balls, config.start.lift, config.lift_angle());
    for (i, &th) in theta.iter().enumerate() {
        let pivot = layout.pivot(i);
        let ball = ball_transform(pivot, c.length, th);
        world.spawn((
            Ball,
            Pendulum {
                index: i,
                pivot,
                length: c.length,
            },
            ball,
            Shape::Sphere { radius: c.radius },
            ball_mat,
        ));
        let top = attach_point(&ball, c.radius);
        for side in [-1.0, 1.0] {
            let anchor = pivot + DVec3::Z * (side * c.rail_spread);
            world.spawn((
                Strand,
                StrandOf { ball: i, anchor },
                Transform::segment(anchor, top),
                Shape::Cylinder {
                    radius: c.string_radius,
                    length: (top - anchor).length(),
                },
                string_mat,
            ));
        }
    }
    let (x, h, s, fr) = (
        layout.half_width,
        c.pivot_height,
        c.rail_spread,
        c.frame_radius,
    );
    let mut rod = |a: DVec3, b: DVec3| {
        world.spawn((
            Rod,
            Transform::segment(a, b),
            Shape::Cylinder {
                radius: fr,
                length: (b - a).length(),
            },
            frame_mat,
        ));
    };
    for z in [-s, s] {
        // Top rail, base rail and the two posts of each side.
        rod(DVec3::new(-x, h, z), DVec3::new(x, h, z));
        rod(DVec3::new(-x, fr, z), DVec3::new(x, fr, z));
        rod(DVec3::new(-x, fr, z), DVec3::new(-x, h, z));
        rod(DVec3::new(x, fr, z), DVec3::new(x, h, z));
    }
    for px in [-x, x] {
        // Cross bars joining the two sides at the top and the base.
        rod(DVec3::new(px, h, -s), DVec3::new(px, h, s));
        rod(DVec3::new(px, fr, -s), DVec3::new(px, fr, s));
    }
    world.spawn((
        Floor,
        Transform::at(DVec3::ZERO),
        Shape::Plane,
        material(&m.floor),
    ));
    for light in &config.lights {
        world.spawn(Light(view::light(light)));
    }
}
