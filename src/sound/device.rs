//! Where the audio thread's samples go: the desktop's audio server. On Linux
//! that is any server speaking the PulseAudio protocol (PulseAudio itself or
//! PipeWire's pulse server), reached by a pure-Rust client, so nothing links a
//! system audio library; on macOS and Windows, cpal's native output.

/// A stream of 48 kHz, 16-bit stereo the audio thread writes to.
pub trait Device: Send {
    /// Blocks until the stream wants more; returns how many frames it wants and
    /// when (s since `epoch`) the first of them will be heard.
    ///
    /// # Errors
    /// The server went away or refused the stream.
    fn wanted(&mut self, epoch: std::time::Instant) -> anyhow::Result<(usize, f64)>;

    /// Queues interleaved left/right samples, as many frames as last wanted.
    ///
    /// # Errors
    /// The server went away.
    fn write(&mut self, samples: &[i16]) -> anyhow::Result<()>;

    /// Times the server ran out of sound to play so far.
    fn underruns(&self) -> u64;
}

/// Opens the desktop's audio output.
///
/// # Errors
/// No audio server reachable, or it refused the stream: the window then runs
/// silently and logs this.
pub fn open() -> anyhow::Result<Box<dyn Device>> {
    #[cfg(target_os = "linux")]
    {
        super::pulse::Pulse::open().map(|d| Box::new(d) as Box<dyn Device>)
    }
    #[cfg(any(target_os = "macos", target_os = "windows"))]
    {
        super::native::Native::open().map(|d| Box::new(d) as Box<dyn Device>)
    }
    #[cfg(not(any(target_os = "linux", target_os = "macos", target_os = "windows")))]
    {
        anyhow::bail!("no audio output on this system")
    }
}
