//! The cradle's sound, beside the picture: each impact the physics reports
//! becomes a click (`synth`: made from the impact's speed, or its measured
//! Hertz contact, panned to where it is on screen). The window plays them live
//! on an audio thread (`live`, writing to the desktop's audio server through
//! `device`); `render --audio` lays them on a WAV soundtrack (`track`).

pub mod device;
pub mod live;
#[cfg(any(target_os = "macos", target_os = "windows"))]
mod native;
#[cfg(target_os = "linux")]
mod pulse;
pub mod synth;
pub mod track;

pub use live::{Sound, Stats};
pub use synth::{Click, Mixer, RATE, Timbre};
