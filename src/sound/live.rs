//! The window's sound: the frame loop hands each frame's impacts to [`Sound`],
//! which sends them as clicks to an audio thread that lays them on the stream
//! the desktop's audio server plays. The frame loop never waits on it: sending
//! is a channel push, and the thread blocks only on the server.
//!
//! Timing: a click is due `LEAD` after the frame that shows its impact, moved
//! back by how long before that frame (in wall time) the impact happened, so
//! clicks keep their spacing at any time rate. The thread places it on the
//! stream where the server's own clock says that moment will be heard, and
//! keeps count of how late each was heard against its frame.

use super::device::Device;
use super::synth::{Click, Mixer, RATE};
use std::sync::mpsc::{self, Receiver, Sender};
use std::time::{Duration, Instant};

/// How long after the frame that shows an impact its click is due (s): about
/// what the stream keeps queued ahead of what is heard, so that the click can
/// still be placed in time.
const LEAD: f64 = 0.04;

/// What the frame loop tells the audio thread.
enum Msg {
    /// A click (its `at` in seconds since the sound's epoch), shown by the
    /// frame presented at `shown` (same clock).
    Play { click: Click, shown: f64 },
    /// The level every click is heard at, 0..=1.
    Volume(f64),
    /// Drop every click not yet heard: the swing was paused, reset or grabbed.
    Flush,
    /// Finish and report.
    Stop,
}

/// What the audio thread measured, reported when it stops.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Stats {
    /// Clicks played.
    pub clicks: u64,
    /// How late each click was heard after the frame that showed it (s), by
    /// the server's clock.
    pub late: Vec<f64>,
    /// Times the server ran out of sound to play.
    pub underruns: u64,
    /// CPU time of the audio thread and the wall time it ran (s).
    pub cpu: f64,
    pub wall: f64,
}

impl Stats {
    /// One log line: clicks, lateness, underruns, CPU.
    #[must_use]
    pub fn line(&self) -> String {
        let mut late = self.late.clone();
        late.sort_by(f64::total_cmp);
        let lateness = if late.is_empty() {
            String::new()
        } else {
            format!(
                ", heard {:.0} ms (median) and at most {:.0} ms after their frames",
                1e3 * late[late.len() / 2],
                1e3 * late[late.len() - 1]
            )
        };
        format!(
            "sound: {} clicks{lateness}; {} underruns; the audio thread used {:.2}% of a core",
            self.clicks,
            self.underruns,
            100.0 * self.cpu / self.wall.max(1e-9)
        )
    }
}

/// The window's sound: on when an audio server took the stream, silent
/// otherwise (the reason logged once).
pub struct Sound {
    link: Option<Link>,
    epoch: Instant,
    muted: bool,
    volume: f64,
}

struct Link {
    tx: Sender<Msg>,
    done: Receiver<Stats>,
}

impl Sound {
    /// Starts the sound at `volume` (0..=1), muted if `muted`, on `device` if
    /// one could be opened (else silent, with the reason logged).
    #[must_use]
    pub fn start(device: anyhow::Result<Box<dyn Device>>, volume: f64, muted: bool) -> Self {
        let epoch = Instant::now();
        let link = match device {
            Ok(device) => {
                let (tx, rx) = mpsc::channel();
                let (done_tx, done) = mpsc::channel();
                let spawned = std::thread::Builder::new()
                    .name("sound".into())
                    .spawn(move || {
                        let stats = play(device, &rx, epoch, volume);
                        let _ = done_tx.send(stats);
                    });
                match spawned {
                    Ok(_) => Some(Link { tx, done }),
                    Err(e) => {
                        tracing::info!("sound off: no audio thread ({e})");
                        None
                    }
                }
            }
            Err(e) => {
                tracing::info!("sound off: {e:#}");
                None
            }
        };
        Self {
            link,
            epoch,
            muted,
            volume,
        }
    }

    /// A sound that plays nothing (headless use, tests).
    #[must_use]
    pub fn silent() -> Self {
        Self {
            link: None,
            epoch: Instant::now(),
            muted: false,
            volume: 1.0,
        }
    }

    /// Whether an audio server plays the clicks.
    #[must_use]
    pub fn is_on(&self) -> bool {
        self.link.is_some()
    }

    /// Muted (the M key).
    #[must_use]
    pub fn is_muted(&self) -> bool {
        self.muted
    }

    /// Mutes or unmutes; muting drops the clicks not yet heard.
    pub fn set_muted(&mut self, muted: bool) {
        if muted && !self.muted {
            self.flush();
        }
        self.muted = muted;
    }

    /// The level clicks are heard at, 0..=1 (the panel's slider, `sound.volume`).
    pub fn set_volume(&mut self, volume: f64) {
        if volume != self.volume {
            self.volume = volume;
            self.send(Msg::Volume(volume));
        }
    }

    /// Drops the clicks not yet heard: nothing stale sounds after a pause, a
    /// reset or a grab.
    pub fn flush(&mut self) {
        self.send(Msg::Flush);
    }

    /// Plays `clicks`, each `at` its impact's time in wall seconds before
    /// (negative) the frame presented at `shown`.
    pub fn play(&mut self, clicks: impl IntoIterator<Item = Click>, shown: Instant) {
        if self.muted || self.link.is_none() {
            return;
        }
        let frame = shown.saturating_duration_since(self.epoch).as_secs_f64();
        for mut click in clicks {
            click.at = frame + click.at + LEAD;
            self.send(Msg::Play {
                click,
                shown: frame,
            });
        }
    }

    fn send(&mut self, msg: Msg) {
        if let Some(link) = &self.link
            && link.tx.send(msg).is_err()
        {
            tracing::info!("sound off: the audio thread ended");
            self.link = None;
        }
    }

    /// Stops the audio thread and returns what it measured (`None` when off, or
    /// when the server does not let it finish within a second).
    pub fn stop(&mut self) -> Option<Stats> {
        let link = self.link.take()?;
        let _ = link.tx.send(Msg::Stop);
        link.done.recv_timeout(Duration::from_secs(1)).ok()
    }
}

impl Drop for Sound {
    fn drop(&mut self) {
        if let Some(stats) = self.stop() {
            tracing::info!("{}", stats.line());
        }
    }
}

/// The audio thread: fills what `device` asks for with the clicks sent on `rx`
/// until told to stop or the device fails.
fn play(mut device: Box<dyn Device>, rx: &Receiver<Msg>, epoch: Instant, volume: f64) -> Stats {
    let cpu = cpu_time::ThreadTime::now();
    let mut stats = Stats::default();
    let mut mixer = Mixer::default();
    let mut volume = volume;
    // Frames written so far: the stream's own clock, frame n at n / RATE s.
    let mut written: u64 = 0;
    let mut buf: Vec<f32> = Vec::new();
    let mut pcm: Vec<i16> = Vec::new();
    let mut due: Vec<(Click, f64)> = Vec::new();
    'playing: loop {
        let (frames, heard_at) = match device.wanted(epoch) {
            Ok(w) => w,
            Err(e) => {
                tracing::info!("sound off: {e:#}");
                break;
            }
        };
        // The stream's time of the next frame written, and where on the epoch's
        // clock it will be heard.
        let stream_now = written as f64 / f64::from(RATE);
        loop {
            match rx.try_recv() {
                Ok(Msg::Play { click, shown }) => due.push((click, shown)),
                Ok(Msg::Volume(v)) => volume = v,
                Ok(Msg::Flush) => {
                    due.clear();
                    mixer.clear();
                }
                Ok(Msg::Stop) | Err(mpsc::TryRecvError::Disconnected) => break 'playing,
                Err(mpsc::TryRecvError::Empty) => break,
            }
        }
        for (mut click, shown) in due.drain(..) {
            // Due before the next frame can be heard: as soon as it can.
            let wait = (click.at - heard_at).max(0.0);
            stats.late.push(heard_at + wait - shown);
            stats.clicks += 1;
            click.at = stream_now + wait;
            mixer.add(click);
        }
        buf.resize(2 * frames, 0.0);
        mixer.fill(written, volume, &mut buf);
        pcm.clear();
        pcm.extend(buf.iter().map(|v| super::synth::pcm(*v)));
        if let Err(e) = device.write(&pcm) {
            tracing::info!("sound off: {e:#}");
            break;
        }
        written += frames as u64;
    }
    stats.underruns = device.underruns();
    stats.cpu = cpu.elapsed().as_secs_f64();
    stats.wall = epoch.elapsed().as_secs_f64();
    stats
}

#[cfg(test)]
mod tests {
    use super::{Device, Sound};
    use crate::sound::synth::{Click, RATE};
    use std::sync::{Arc, Mutex};
    use std::time::{Duration, Instant};

    /// A device that wants 10 ms at a time, heard 20 ms after it is asked,
    /// keeping what it was given.
    struct Tape {
        frames: Arc<Mutex<Vec<i16>>>,
    }

    impl Device for Tape {
        fn wanted(&mut self, epoch: Instant) -> anyhow::Result<(usize, f64)> {
            std::thread::sleep(Duration::from_millis(10));
            Ok((480, epoch.elapsed().as_secs_f64() + 0.02))
        }
        fn write(&mut self, samples: &[i16]) -> anyhow::Result<()> {
            self.frames.lock().unwrap().extend_from_slice(samples);
            Ok(())
        }
        fn underruns(&self) -> u64 {
            0
        }
    }

    fn click() -> Click {
        Click {
            at: -0.005,
            level: 0.5,
            pulse: 1.3e-4,
            pan: 0.0,
        }
    }

    fn run(muted: bool) -> (Vec<i16>, super::Stats) {
        let frames = Arc::new(Mutex::new(Vec::new()));
        let tape = Tape {
            frames: frames.clone(),
        };
        let mut sound = Sound::start(Ok(Box::new(tape)), 1.0, muted);
        std::thread::sleep(Duration::from_millis(50));
        sound.play([click()], Instant::now());
        std::thread::sleep(Duration::from_millis(300));
        let stats = sound.stop().expect("the thread reports");
        let tape = frames.lock().unwrap().clone();
        (tape, stats)
    }

    #[test]
    fn a_click_sent_is_heard_soon_after_its_frame() {
        let (tape, stats) = run(false);
        assert_eq!(stats.clicks, 1);
        // Due 35 ms after its frame (40 ms lead, 5 ms before the frame); the
        // tape hears what it is given 20 ms on, so it can be placed there: heard
        // no sooner than due (a thread slow to wake on a loaded machine only
        // delays it further, never advances it; 0.1 ms is round-off to spare).
        assert!(stats.late[0] >= 0.0349, "{:?}", stats.late);
        let loud = tape.iter().filter(|v| v.unsigned_abs() > 1000).count();
        assert!(loud > 0, "the click is on the tape");
        assert!(tape.len() >= 2 * 480 * 10, "{} samples", tape.len());
        assert!(tape.len() % 2 == 0 && f64::from(RATE) > 0.0);
    }

    #[test]
    fn a_muted_sound_plays_silence() {
        let (tape, stats) = run(true);
        assert_eq!(stats.clicks, 0);
        assert!(!tape.is_empty() && tape.iter().all(|v| *v == 0));
    }

    #[test]
    fn without_a_device_the_sound_is_off_and_says_so() {
        let mut sound = Sound::start(Err(anyhow::anyhow!("no audio server")), 1.0, false);
        assert!(!sound.is_on());
        sound.play([click()], Instant::now());
        assert!(sound.stop().is_none());
    }
}
