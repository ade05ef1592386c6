//! The tracer's side of the pipeline. The extract stage turns the ECS world into a
//! flat, plain-data [`Scene`] each frame; the tracer reads only that.

pub mod scene;

pub use scene::{Camera, Light, Material, Object, Scene, Shape};
