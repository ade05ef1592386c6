//! The ECS world: components (`components`), spawning from a config (`spawn`,
//! with the tracer's camera, lights and settings from `view`), the frame's
//! systems (`systems`; `record`: what the graphs read), and [`CradleWorld`],
//! which owns the world and the frame schedule of chained sets Input ->
//! Physics -> Extract.

pub mod components;
pub mod fit;
pub mod layout;
pub mod long_row;
pub mod record;
pub mod spawn;
pub mod systems;
pub mod view;

pub use components::{CradleState, FlatScene, FrameImpacts, SimClock, SimState};

use crate::config::Config;
use bevy_ecs::prelude::*;

/// The stages of a frame, run in this order.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub enum FrameSet {
    /// The clock (the app sets the run state directly, between frames).
    Input,
    /// The cradle's state; ball and string transforms.
    Physics,
    /// The flat scene for the tracer.
    Extract,
}

/// The frame schedule.
#[must_use]
pub fn frame_schedule() -> Schedule {
    let mut schedule = Schedule::default();
    schedule.configure_sets((FrameSet::Input, FrameSet::Physics, FrameSet::Extract).chain());
    schedule.add_systems(systems::advance_clock.in_set(FrameSet::Input));
    schedule.add_systems(
        (
            systems::step_physics,
            systems::place_balls,
            systems::place_strands,
            record::record,
        )
            .chain()
            .in_set(FrameSet::Physics),
    );
    schedule.add_systems(
        (systems::apply_view, systems::extract)
            .chain()
            .in_set(FrameSet::Extract),
    );
    schedule
}

/// The world and its frame schedule.
pub struct CradleWorld {
    /// The ECS world.
    pub world: World,
    schedule: Schedule,
}

impl CradleWorld {
    /// A world spawned from `config`.
    #[must_use]
    pub fn new(config: &Config) -> Self {
        Self {
            world: spawn::build_world(config),
            schedule: frame_schedule(),
        }
    }

    /// Starts or stops the swing, at once: the next frame sees it, and so does a
    /// respawn before that frame.
    pub fn set_running(&mut self, running: bool) {
        *self.world.resource_mut::<SimState>() = if running {
            SimState::Running
        } else {
            SimState::Paused
        };
    }

    /// Runs one frame that lasted `dt` seconds of wall-clock time.
    pub fn frame(&mut self, dt: f64) {
        self.frame_by(dt, None);
    }

    /// Runs one frame that lasted `dt` seconds, its physics done by `deadline`
    /// (where given): a cradle too slow for it shows the latest time it reached.
    pub fn frame_by(&mut self, dt: f64, deadline: Option<std::time::Instant>) {
        let mut clock = self.world.resource_mut::<SimClock>();
        clock.frame_dt = dt;
        clock.deadline = deadline;
        self.schedule.run(&mut self.world);
    }

    /// Runs one frame showing the cradle at simulated time `t` (s), running or not:
    /// headless rendering picks its times directly instead of summing frame times.
    pub fn show_at(&mut self, t: f64) {
        let mut clock = self.world.resource_mut::<SimClock>();
        clock.t = t;
        clock.frame_dt = 0.0;
        clock.deadline = None;
        self.schedule.run(&mut self.world);
    }

    /// Works the physics out up to time `t` (s) a second of work at a time,
    /// telling `progress` the time reached after each: a far `t` (`render
    /// --time 1e6`) takes minutes. The states are those [`Self::show_at`] gives.
    pub fn reach(&mut self, t: f64, mut progress: impl FnMut(f64)) {
        loop {
            let deadline = std::time::Instant::now() + std::time::Duration::from_secs(1);
            let reached = self
                .world
                .resource_mut::<CradleState>()
                .cradle
                .snapshot_by(t, deadline)
                .t;
            if reached >= t {
                return;
            }
            progress(reached);
        }
    }

    /// Replaces the scene by one spawned from `config`, at t = 0, running as
    /// `config.start.running` says: the one way to reset.
    pub fn respawn(&mut self, config: &Config) {
        spawn::respawn(&mut self.world, config);
    }

    /// Restarts the cradle of `config` from angles `theta` (rad), at rest, at
    /// t = 0: the physics exactly from that state. The box the moving objects stay
    /// in follows the new energy (`lifted` balls at `angle`, the state's bound).
    pub fn start_from(&mut self, config: &Config, theta: &[f64], lifted: usize, angle: f64) {
        let cradle = crate::physics::Cradle::from_state(
            config.cradle_params(),
            config.physics.integrator,
            config.physics.dt,
            theta,
            &vec![0.0; theta.len()],
        );
        self.world.insert_resource(CradleState::new(cradle));
        let mut bound = config.clone();
        bound.start.lift = lifted;
        bound.start.angle_deg = angle.to_degrees();
        let (lo, hi) = view::motion_bounds(&bound);
        self.world.insert_resource(components::SwingBox(lo, hi));
        self.show_at(0.0);
    }

    /// Traces at `quality` from the next frame on: a change the running
    /// swing absorbs.
    pub fn set_quality(&mut self, quality: components::Quality) {
        self.world
            .resource_mut::<components::Quality>()
            .set_if_neq(quality);
    }

    /// Looks through `camera` from the next frame on (the user's view; a respawn
    /// returns to the asset's).
    pub fn set_camera(&mut self, camera: crate::trace::Camera) {
        self.world
            .resource_mut::<components::View>()
            .set_if_neq(components::View(camera));
    }

    /// The flat scene of the last frame.
    #[must_use]
    pub fn scene(&self) -> &crate::trace::Scene {
        &self.world.resource::<FlatScene>().scene
    }

    /// What changed in the flat scene since the last call (everything, the
    /// first time and after a respawn): for the tracer's incremental frames
    /// (`Incremental::render_changed`).
    pub fn take_change(&mut self) -> crate::trace::Change {
        let mut flat = self.world.resource_mut::<FlatScene>();
        std::mem::replace(
            &mut flat.bypass_change_detection().change,
            crate::trace::Change::none(),
        )
    }

    /// Running or paused.
    #[must_use]
    pub fn state(&self) -> SimState {
        *self.world.resource::<SimState>()
    }

    /// Records the physics for the graphs from the next frame on, or stops
    /// (and forgets what was recorded).
    pub fn set_recording(&mut self, on: bool) {
        let mut rec = self.world.resource_mut::<record::Recording>();
        if !on {
            rec.clear();
        }
        rec.on = on;
    }

    /// What the graphs read.
    #[must_use]
    pub fn recording(&self) -> &record::Recording {
        self.world.resource::<record::Recording>()
    }

    /// The impacts of the last frame (none while paused).
    #[must_use]
    pub fn impacts(&self) -> &FrameImpacts {
        self.world.resource::<FrameImpacts>()
    }

    /// The physics state of the last frame.
    #[must_use]
    pub fn cradle(&self) -> &CradleState {
        self.world.resource::<CradleState>()
    }
}
