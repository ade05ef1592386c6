//! ECS components, markers, resources and messages of the cradle world.

use crate::physics::{Course, Cradle, Impact, Snapshot};
use crate::trace;
use bevy_ecs::prelude::*;
use glam::{DQuat, DVec3};

/// Where an entity is: world-space position and orientation (f64, like the physics).
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    /// Position (m).
    pub translation: DVec3,
    /// Orientation.
    pub rotation: DQuat,
}

impl Transform {
    /// A transform at `translation` with no rotation.
    #[must_use]
    pub fn at(translation: DVec3) -> Self {
        Self {
            translation,
            rotation: DQuat::IDENTITY,
        }
    }

    /// The transform of a cylinder from `a` to `b` (its local +y axis along `b - a`).
    #[must_use]
    pub fn segment(a: DVec3, b: DVec3) -> Self {
        Self {
            translation: 0.5 * (a + b),
            rotation: DQuat::from_rotation_arc(DVec3::Y, (b - a).normalize()),
        }
    }
}

/// An entity's shape in its local frame.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A sphere about the origin.
    Sphere { radius: f64 },
    /// A capped cylinder along local y, centred on the origin.
    Cylinder { radius: f64, length: f64 },
    /// The plane y = 0, facing +y.
    Plane,
}

/// An entity's look (linear RGB).
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct Material(pub trace::Material);

/// Marks a ball.
#[derive(Component, Debug, Clone, Copy)]
pub struct Ball;

/// Marks a string (the design's `String`, named so as not to shadow std's).
#[derive(Component, Debug, Clone, Copy)]
pub struct Strand;

/// Marks a rod of the frame.
#[derive(Component, Debug, Clone, Copy)]
pub struct Rod;

/// Marks the floor.
#[derive(Component, Debug, Clone, Copy)]
pub struct Floor;

/// A ball's pendulum: its index (0 = leftmost), pivot (m) and length (m).
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct Pendulum {
    /// Ball index from the left.
    pub index: usize,
    /// Midpoint of the two rail anchors: the swing axis passes through it along z.
    pub pivot: DVec3,
    /// Pivot to ball centre (m).
    pub length: f64,
}

/// Which ball a string holds and where on the rail it is tied.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct StrandOf {
    /// Ball index.
    pub ball: usize,
    /// The string's end on the rail (m).
    pub anchor: DVec3,
}

/// A light source entity, as the tracer takes it.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct Light(pub trace::Light);

/// Running or paused.
#[derive(Resource, Debug, Clone, Copy, PartialEq, Eq)]
pub enum SimState {
    /// The clock runs.
    Running,
    /// The clock stands still.
    Paused,
}

/// Simulated time (s) and the wall-clock length of the frame being run (s).
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq)]
pub struct SimClock {
    /// Simulated time.
    pub t: f64,
    /// Length of this frame, set by the driver before each run of the schedule.
    pub frame_dt: f64,
    /// When the physics of this frame must be done (the window's frame loop):
    /// a cradle that cannot reach the clock's time by then shows the latest
    /// time it reached, and the clock waits there (slow motion). `None`:
    /// exactly the clock's time, however long it takes (headless).
    pub deadline: Option<std::time::Instant>,
}

/// The physics and its latest state.
#[derive(Resource, Debug, Clone)]
pub struct CradleState {
    /// The cradle.
    pub cradle: Cradle,
    /// Its state at the clock's time.
    pub snapshot: Snapshot,
}

impl CradleState {
    /// `cradle` at t = 0, keeping its impacts for [`FrameImpacts`].
    #[must_use]
    pub fn new(mut cradle: Cradle) -> Self {
        cradle.record_impacts();
        let snapshot = cradle.snapshot(0.0);
        Self { cradle, snapshot }
    }

    /// Each ball's share of the starting energy; the share left in all, and its
    /// relative error (of the energy balance when the cradle dissipates).
    #[must_use]
    pub fn energies(&self) -> (Vec<f64>, (f64, f64)) {
        let p = self.cradle.params();
        let e0 = self.cradle.initial_energy();
        let s = &self.snapshot;
        let shares = s
            .theta
            .iter()
            .zip(&s.omega)
            .map(|(&t, &w)| {
                if e0 > 0.0 {
                    p.ball_energy(t, w) / e0
                } else {
                    0.0
                }
            })
            .collect();
        let left = if e0 > 0.0 {
            self.cradle.energy(s) / e0
        } else {
            1.0
        };
        (shares, (left, self.cradle.energy_rel_error(s)))
    }
}

/// The impacts of the last frame: those after the previous frame's time, up
/// to this one's (none while paused). The sound reads them, the graphs their
/// courses.
#[derive(Resource, Debug, Clone, Default)]
pub struct FrameImpacts {
    /// Earliest first.
    pub impacts: Vec<Impact>,
    /// Their courses, earliest first, while the cradle keeps them (the graphs
    /// are open): a Hertz contact's is handed out once it has ended.
    pub courses: Vec<Course>,
    /// The first ball's pivot in the world (m): an impact's contact point
    /// `at` is `(origin.x + at.0, origin.y + at.1, origin.z)`.
    pub origin: DVec3,
}

impl FrameImpacts {
    /// Where impact `i` is in the world (m).
    #[must_use]
    pub fn place(&self, i: &Impact) -> DVec3 {
        self.origin + DVec3::new(i.at.0, i.at.1, 0.0)
    }
}

/// The flat scene for the tracer: its background and size are set at spawn,
/// its camera and quality by `apply_view`, its objects and lights by the
/// extract stage each frame; with what changed since the tracer last took
/// it (`CradleWorld::take_change`), from the components' change ticks.
#[derive(Resource, Debug, Clone, Default)]
pub struct FlatScene {
    /// The scene.
    pub scene: trace::Scene,
    /// What changed since the tracer last took it.
    pub change: trace::Change,
}

/// The camera the user looks through: the asset's fitted one at spawn, then
/// orbit, pan, zoom and camera reset.
#[derive(Resource, Debug, Clone, Copy, PartialEq)]
pub struct View(pub trace::Camera);

/// How the tracer samples a pixel: samples per pixel, the adaptive
/// threshold (`None`: every pixel at every sample), and the blocks of pixels
/// traced with one ray each (1: every pixel; more while the view moves).
#[derive(Resource, Debug, Clone, Copy, PartialEq)]
pub struct Quality {
    /// Samples per pixel.
    pub samples: u32,
    /// Adaptive anti-aliasing's threshold.
    pub adaptive: Option<f32>,
    /// Pixels per side of a block traced with one ray (`Scene::coarse`).
    pub coarse: u32,
}

impl Quality {
    /// While the view moves: one ray per 2x2 block of pixels (a quarter of
    /// the rays, so a drag keeps up), no anti-aliasing.
    pub const MOVING: Self = Self {
        samples: 1,
        adaptive: None,
        coarse: 2,
    };

    /// At rest: the asset's samples and adaptive threshold, every pixel traced.
    #[must_use]
    pub fn at_rest(r: &crate::config::RenderConfig) -> Self {
        Self {
            samples: r.samples,
            adaptive: r.adaptive.then_some(r.adaptive_threshold as f32),
            coarse: 1,
        }
    }

    /// Sets `scene`'s sampling to this.
    pub fn set_on(self, scene: &mut trace::Scene) {
        scene.samples = self.samples;
        scene.adaptive = self.adaptive;
        scene.coarse = self.coarse;
    }
}

/// The box the balls and strings stay in at every time, at their true
/// thickness (min, max corners): extract widens it by what it adds to far
/// strings, and hands it to the tracer as the scene's motion bounds.
#[derive(Resource, Debug, Clone, Copy, PartialEq)]
pub struct SwingBox(pub glam::Vec3, pub glam::Vec3);
