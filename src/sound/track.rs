//! `render --audio FILE.wav`: the soundtrack of a rendered run of frames. The
//! frames' impacts are gathered as they are rendered and laid on a track that
//! starts at the first frame's time and lasts exactly frames / fps seconds
//! (rounded to the nearest sample), each click starting on the first sample at
//! or after its impact's exact time.

use super::synth::{Click, Mixer, RATE, Timbre};
use crate::config::Config;
use crate::export::{self, WriteError};
use crate::scene::FrameImpacts;
use crate::trace;
use std::path::Path;

/// A soundtrack being gathered.
#[derive(Debug, Clone)]
pub struct Soundtrack {
    /// Simulated time of the track's first sample (s).
    start: f64,
    /// Samples per channel.
    frames: u64,
    timbre: Timbre,
    clicks: Vec<Click>,
}

impl Soundtrack {
    /// An empty track of `seconds` from simulated time `start` (s), for the
    /// cradle of `config`.
    #[must_use]
    pub fn new(config: &Config, start: f64, seconds: f64) -> Self {
        Self {
            start,
            frames: (seconds * f64::from(RATE)).round() as u64,
            timbre: timbre(config),
            clicks: Vec::new(),
        }
    }

    /// A track of `seconds` with `clicks` already laid on it (their times from
    /// its start): the window's replay, whose clicks were heard live.
    #[must_use]
    pub fn laid(timbre: Timbre, seconds: f64, clicks: Vec<Click>) -> Self {
        Self {
            start: 0.0,
            frames: (seconds * f64::from(RATE)).round() as u64,
            timbre,
            clicks,
        }
    }

    /// The simulated time the track starts at (s).
    #[must_use]
    pub fn start(&self) -> f64 {
        self.start
    }

    /// The simulated time the track ends at (s).
    #[must_use]
    pub fn end(&self) -> f64 {
        self.start + self.frames as f64 / f64::from(RATE)
    }

    /// Adds the clicks of a frame's impacts that fall on the track, panned to
    /// where `scene`'s camera sees them.
    pub fn hear(&mut self, impacts: &FrameImpacts, scene: &trace::Scene) {
        for i in &impacts.impacts {
            let at = i.t - self.start;
            if at < 0.0 || i.t >= self.end() {
                continue;
            }
            let pan = pan_in(scene, impacts.place(i));
            if let Some(c) = Click::of(i, &self.timbre, at, pan) {
                self.clicks.push(c);
            }
        }
    }

    /// The clicks on the track so far.
    #[must_use]
    pub fn clicks(&self) -> &[Click] {
        &self.clicks
    }

    /// Writes the track as a 48 kHz, 16-bit stereo WAV, atomically.
    ///
    /// # Errors
    /// When the file cannot be written.
    pub fn write(&self, path: &Path) -> Result<(), WriteError> {
        let mut clicks = self.clicks.clone();
        clicks.sort_by(|a, b| a.at.total_cmp(&b.at));
        let mut next = clicks.into_iter().peekable();
        let mut mixer = Mixer::default();
        let mut mix = Vec::new();
        export::write_wav(path, RATE, self.frames, |first, out| {
            let end = (first + out.len() as u64 / 2) as f64 / f64::from(RATE);
            while let Some(c) = next.next_if(|c| c.at < end) {
                mixer.add(c);
            }
            mix.resize(out.len(), 0.0);
            mixer.fill(first, 1.0, &mut mix);
            for (o, m) in out.iter_mut().zip(&mix) {
                *o = super::synth::pcm(*m);
            }
        })
    }
}

/// The timbre of the cradle of `config`: its balls and material.
#[must_use]
pub fn timbre(config: &Config) -> Timbre {
    let p = config.cradle_params();
    Timbre::new(
        config.contact.youngs_modulus,
        config.contact.poisson_ratio,
        p.radius,
        p.mass,
    )
}

/// Where on `scene`'s picture a point of the world is heard, -1 (left edge) to
/// 1 (right edge); 0 when the camera does not see it.
#[must_use]
pub fn pan_in(scene: &trace::Scene, point: glam::DVec3) -> f64 {
    let (w, h) = scene.size;
    trace::camera::CameraRays::new(&scene.camera, w, h)
        .project(point.as_vec3())
        .map_or(0.0, |(x, _)| super::synth::pan(x, w))
}
