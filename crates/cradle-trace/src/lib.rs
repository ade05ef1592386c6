//! cradle-trace: the CPU ray tracer of newtons-cradle. Plain data in, pixels out;
//! it depends on no ECS, window or GPU crate.
//!
//! The app's extract stage turns its ECS world into a flat [`Scene`] each frame.
//! Then, in data-flow order:
//! - [`scene`]: the flat scene (shapes, materials, lights, camera) in f32;
//! - [`prepared`], [`bvh`], [`tiles`], [`shadow`]: bounds and culling structures
//!   built once per frame ([`Prepared`]); `wide` tests eight boxes at once, in
//!   the AVX2 or the portable build (`simd`);
//! - [`camera`], [`geometry`], [`reference`], `shade`: rays, hit tests,
//!   Whitted shading (the reference) and its fast scalar path;
//! - [`sampling`], [`render`]: sample offsets and the serial and parallel render
//!   twins ([`render`], [`render_serial`]);
//! - [`motion`], `retrace`, [`incremental`], `adaptive`: motion cells and ray
//!   segments, and incremental frames ([`Incremental`]), anti-aliased too;
//! - [`color`]: linear colour to sRGB bytes in an RGBA8 [`Image`].

mod adaptive;
mod bits;
pub mod bvh;
pub mod camera;
mod casters;
pub mod color;
mod frame;
pub mod geometry;
pub mod incremental;
pub mod material;
pub mod motion;
pub mod packet;
pub mod prepared;
pub mod reference;
pub mod render;
mod retrace;
pub mod sampling;
pub mod scene;
mod shade;
pub mod shadow;
mod simd;
mod stretch;
mod supersample;
pub mod tiles;
mod tuning;
mod wide;

pub use color::{Image, srgb8};
pub use incremental::{Change, Changes, Incremental, Lent};
pub use prepared::Prepared;
pub use render::{
    RenderOptions, pool, render, render_counting, render_serial, render_serial_with, render_with,
};
pub use scene::{Camera, Light, Material, Object, Scene, Shape};
