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
//! - [`trace`]: the CPU ray tracer over the flat scene the extract stage fills.
//! - [`export`], [`headless`]: PNG and GIF output, the `render` subcommand.
//! - [`bench`]: `bench render` (ms per frame over thread counts), `render-quality`
//!   (picture error against time), `physics` (work-precision) and `stress`.
//! - [`app`]: the window (winit + pixels), keys, HUD and hot reload.
//! - [`simulate`]: the `simulate` subcommand's JSON Lines.

#![forbid(unsafe_code)]

pub mod app;
pub mod bench;
pub mod cli;
pub mod config;
pub mod export;
pub mod headless;
pub use cradle_physics as physics;
pub mod scene;
pub mod simulate;
pub mod sound;
pub use cradle_trace as trace;
