//! Where the audio thread's samples go: the desktop's audio server, behind one
//! trait (`pulse` on Linux, `native` on macOS and Windows; [`super::output`]
//! opens the one there is).

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
