//! The macOS and Windows audio output: cpal's native stream (Core Audio,
//! WASAPI), which needs no extra package there.
//!
//! cpal pulls samples from a callback on its own thread; the audio thread
//! keeps a queue of about 30 ms ahead of it. The stream itself lives on a
//! small holder thread (it may not move between threads), dropped with
//! [`Native`].

use super::device::Device;
use super::synth::RATE;
use anyhow::{Context, anyhow};
use cpal::traits::{DeviceTrait, HostTrait, StreamTrait};
use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

/// What the queue holds ahead of the device (s).
const TARGET: f64 = 0.03;

/// Samples waiting for the callback, and the condition it signals as it takes them.
struct Queue {
    samples: Mutex<VecDeque<i16>>,
    taken: Condvar,
    underruns: AtomicU64,
}

/// The native output stream.
pub struct Native {
    queue: Arc<Queue>,
    /// Dropping it ends the holder thread, and the stream with it.
    _hold: mpsc::Sender<()>,
}

impl Native {
    /// Opens the default output device at 48 kHz stereo.
    ///
    /// # Errors
    /// No output device, or none that plays 48 kHz stereo.
    pub fn open() -> anyhow::Result<Self> {
        let queue = Arc::new(Queue {
            samples: Mutex::new(VecDeque::new()),
            taken: Condvar::new(),
            underruns: AtomicU64::new(0),
        });
        let (hold, held) = mpsc::channel::<()>();
        let (opened_tx, opened) = mpsc::channel();
        let q = queue.clone();
        std::thread::Builder::new()
            .name("sound-device".into())
            .spawn(move || match build(q) {
                Ok(stream) => {
                    let _ = opened_tx.send(Ok(()));
                    // Until `Native` is dropped.
                    let _ = held.recv();
                    drop(stream);
                }
                Err(e) => {
                    let _ = opened_tx.send(Err(e));
                }
            })?;
        opened
            .recv_timeout(Duration::from_secs(5))
            .map_err(|_| anyhow!("the audio output did not open"))??;
        Ok(Self { queue, _hold: hold })
    }
}

/// The playing stream, its callback taking from `queue`.
fn build(queue: Arc<Queue>) -> anyhow::Result<cpal::Stream> {
    let host = cpal::default_host();
    let device = host
        .default_output_device()
        .ok_or_else(|| anyhow!("no audio output device"))?;
    let config = device
        .supported_output_configs()
        .context("the audio output device")?
        .filter(|c| c.channels() == 2 && c.sample_format() == cpal::SampleFormat::F32)
        .find_map(|c| c.try_with_sample_rate(RATE))
        .ok_or_else(|| anyhow!("the audio output device plays no 48 kHz stereo"))?;
    let stream = device
        .build_output_stream(
            config.config(),
            move |data: &mut [f32], _| {
                let mut samples = queue.samples.lock().unwrap_or_else(|e| e.into_inner());
                if samples.len() < data.len() {
                    queue.underruns.fetch_add(1, Ordering::Relaxed);
                }
                for d in data.iter_mut() {
                    *d = samples.pop_front().map_or(0.0, |s| f32::from(s) / 32767.0);
                }
                queue.taken.notify_one();
            },
            |e| tracing::debug!("audio output: {e}"),
            None,
        )
        .context("the audio output refused the stream")?;
    stream.play().context("the audio output does not play")?;
    Ok(stream)
}

impl Device for Native {
    fn wanted(&mut self, epoch: Instant) -> anyhow::Result<(usize, f64)> {
        let target = (TARGET * f64::from(RATE)) as usize * 2;
        let mut samples = self.queue.samples.lock().unwrap_or_else(|e| e.into_inner());
        while samples.len() >= target {
            let (s, timeout) = self
                .queue
                .taken
                .wait_timeout(samples, Duration::from_secs(3))
                .unwrap_or_else(|e| e.into_inner());
            samples = s;
            if timeout.timed_out() && samples.len() >= target {
                anyhow::bail!("the audio output stopped playing");
            }
        }
        let queued = samples.len() as f64 / 2.0 / f64::from(RATE);
        let frames = (target - samples.len()) / 2;
        Ok((frames, epoch.elapsed().as_secs_f64() + queued))
    }

    fn write(&mut self, samples: &[i16]) -> anyhow::Result<()> {
        self.queue
            .samples
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .extend(samples);
        Ok(())
    }

    fn underruns(&self) -> u64 {
        self.queue.underruns.load(Ordering::Relaxed)
    }
}
