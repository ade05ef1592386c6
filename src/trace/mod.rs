//! The CPU ray tracer: plain data in, pixels out; no ECS or window types.
//!
//! The extract stage turns the ECS world into a flat [`Scene`] each frame.
//! [`Prepared`] adds bounds, [`shade::trace`] shades a ray (Whitted), and
//! [`render`] / [`render_serial`] fill an sRGB RGBA8 [`Image`].

pub mod bvh;
pub mod camera;
pub mod geometry;
pub mod prepared;
pub mod render;
pub mod scene;
pub mod shade;
pub mod shadow;
pub mod tiles;

pub use prepared::Prepared;
pub use render::{
    Image, Incremental, RenderOptions, pool, render, render_serial, render_serial_with,
};
pub use scene::{Camera, Light, Material, Object, Scene, Shape};
