//! newtons-cradle: a Newton's cradle ray traced on the CPU, driven by exact physics.
//!
//! The pipeline, each frame:
//! ```text
//! assets/cradle.ron --load+validate--> Config --spawn--> bevy_ecs World
//! input -> physics -> extract -> (trace -> present)
//! ```
//! - [`config`]: the asset, its defaults, validation with located errors.
//! - [`physics`]: exact closed-form pendulum flight and impacts (no ECS types).
//! - [`scene`]: the ECS world: components, spawning, the frame schedule.
//! - [`trace`]: the flat plain-data scene the extract stage fills.
//! - [`simulate`]: the `simulate` subcommand's JSON Lines.

#![forbid(unsafe_code)]

pub mod cli;
pub mod config;
pub mod physics;
pub mod preview;
pub mod scene;
pub mod simulate;
pub mod trace;
