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

/// Opens the desktop's audio output: on Linux any server speaking the
/// PulseAudio protocol (PulseAudio itself or PipeWire's pulse server), reached
/// by a pure-Rust client, so nothing links a system audio library; on macOS and
/// Windows, cpal's native output.
///
/// # Errors
/// No audio server reachable, or it refused the stream: the window then runs
/// silently and logs this.
pub fn output() -> anyhow::Result<Box<dyn device::Device>> {
    #[cfg(target_os = "linux")]
    {
        pulse::Pulse::open().map(|d| Box::new(d) as Box<dyn device::Device>)
    }
    #[cfg(any(target_os = "macos", target_os = "windows"))]
    {
        native::Native::open().map(|d| Box::new(d) as Box<dyn device::Device>)
    }
    #[cfg(not(any(target_os = "linux", target_os = "macos", target_os = "windows")))]
    {
        anyhow::bail!("no audio output on this system")
    }
}
