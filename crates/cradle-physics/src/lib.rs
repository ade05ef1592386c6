//! cradle-physics: the physics core of newtons-cradle. Plain Rust over plain
//! data; it depends on no ECS, window or GPU crate.
//!
//! Each ball is a rigid physical pendulum in one plane. Between impacts it flies in
//! closed form (`flight`, from the Jacobi elliptic functions of `elliptic`);
//! impacts are roots of the neighbours' gap functions (`contact`, `roots`), found
//! by the exact event-driven engine (`exact`). Soft Hertz contact (`hertz`)
//! replaces the instantaneous impacts when asked for, elastic or viscoelastic
//! (`row`); with air drag the damped engine (`damped`) integrates the whole motion. Fixed-step integrators
//! (`stepped`) with the same impacts exist for comparison. `cradle` puts them
//! behind one type; each engine reports its impacts (`impacts`) for the sound.

#![forbid(unsafe_code)]

pub mod contact;
pub mod cradle;
pub mod damped;
mod dopri;
pub mod elliptic;
pub mod exact;
pub mod flight;
pub mod hertz;
pub mod impacts;
pub mod params;
pub mod roots;
mod row;
pub mod stepped;

pub use cradle::{Cradle, Snapshot};
pub use flight::{Flight, period_ratio};
pub use impacts::{Contact, Course, Impact};
pub use params::{CradleParams, Integrator};
