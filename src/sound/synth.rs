//! Clicks made from impacts, and the mixer that lays them on a stereo track at
//! their exact times: the same for the window's audio thread and a WAV file.
//!
//! The model (docs/sound.md says which parts are physics and which are choices):
//! - the force between the pair is Hertz's half-sine pulse of the contact's
//!   duration `tau` and peak force `F`, measured by the physics for Hertz
//!   contact and given by Hertz's law for an ideal impact at its speed;
//! - the pressure a small rigid body radiates follows the rate of change of that
//!   force, so the click's first part is `dF/dt`: a pulse `cos(pi u / tau)` of
//!   height `pi F / tau`, louder and shorter (brighter) the harder the impact;
//! - a ring at the pulse's main frequency `1 / (2 tau)` dies away in 30 ms: the
//!   sound of the cradle around the balls, a choice that makes the tick a click;
//! - each click is panned to where the impact is on screen (equal power), and
//!   the sum goes through a soft limit (`tanh`) so that many at once never clip.

use crate::physics::{Impact, hertz};

/// Samples per second of every track.
pub const RATE: u32 = 48_000;

/// The force rate heard at full scale (N/s): the default cradle's strike
/// (steel, 2 cm balls meeting at 0.65 m/s: 2300 N over 0.13 ms, a pulse of
/// pi F / tau = 5.5e7 N/s) is 0.14 of it per contact, 0.55 over its four.
const FULL_SCALE: f64 = 4.0e8;

/// The ring's height against the pulse's, and its decay time (s).
const RING: f64 = 0.35;
const RING_DECAY: f64 = 0.03;

/// How long a click sounds (s): its ring is then below 1/400 of its start.
pub const CLICK_LENGTH: f64 = 6.0 * RING_DECAY;

/// The pair's contact stiffness and reduced mass: what turns an ideal impact's
/// speed into the force pulse Hertz contact would give.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timbre {
    /// Hertz stiffness (N/m^1.5) of the config's material and balls.
    pub stiffness: f64,
    /// Reduced mass of two balls (kg).
    pub reduced_mass: f64,
}

impl Timbre {
    /// The timbre of two balls of `radius` (m) and `mass` (kg) of a material of
    /// Young's modulus `youngs` (Pa) and Poisson ratio `poisson`.
    #[must_use]
    pub fn new(youngs: f64, poisson: f64, radius: f64, mass: f64) -> Self {
        Self {
            stiffness: hertz::stiffness(youngs, poisson, radius),
            reduced_mass: 0.5 * mass,
        }
    }

    /// The contact's peak force (N) and duration (s) for an impact: measured by
    /// the physics for Hertz contact; from Hertz's law at its speed for an ideal
    /// one (`None` when the balls met at no speed).
    #[must_use]
    pub fn pulse(&self, impact: &Impact) -> Option<(f64, f64)> {
        if let Some(c) = impact.contact {
            return (c.duration > 0.0 && c.peak_force > 0.0).then_some((c.peak_force, c.duration));
        }
        let v = impact.speed;
        if v <= 0.0 || !v.is_finite() {
            return None;
        }
        let deepest = (1.25 * self.reduced_mass * v * v / self.stiffness).powf(0.4);
        let force = self.stiffness * deepest.powf(1.5);
        Some((
            force,
            hertz::contact_time(self.stiffness, self.reduced_mass, v),
        ))
    }
}

/// One click on a track.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Click {
    /// When it starts (s on the track's clock).
    pub at: f64,
    /// Height of its pulse, 1 at full scale.
    pub level: f64,
    /// Length of its pulse (s): the contact's duration.
    pub pulse: f64,
    /// Where it is heard, -1 (left) ..= 1 (right).
    pub pan: f64,
}

impl Click {
    /// The click of `impact` at track time `at` (s), panned to `pan`; `None` for
    /// an impact that makes no sound (met at no speed).
    #[must_use]
    pub fn of(impact: &Impact, timbre: &Timbre, at: f64, pan: f64) -> Option<Self> {
        let (force, tau) = timbre.pulse(impact)?;
        Some(Self {
            at,
            level: std::f64::consts::PI * force / tau / FULL_SCALE,
            pulse: tau,
            pan: pan.clamp(-1.0, 1.0),
        })
    }

    /// The click's sound `u` seconds after it starts (0 before).
    fn value(&self, u: f64) -> f64 {
        if u < 0.0 {
            return 0.0;
        }
        let pulse = if u < self.pulse {
            (std::f64::consts::PI * u / self.pulse).cos()
        } else {
            0.0
        };
        let ring = (std::f64::consts::TAU * u / (2.0 * self.pulse)).sin() * (-u / RING_DECAY).exp();
        self.level * (pulse + RING * ring)
    }

    /// Left and right gains (equal power).
    fn gains(&self) -> (f64, f64) {
        let angle = (self.pan + 1.0) * std::f64::consts::FRAC_PI_4;
        (angle.cos(), angle.sin())
    }
}

/// The clicks sounding on a track, laid down chunk by chunk.
#[derive(Debug, Clone, Default)]
pub struct Mixer {
    clicks: Vec<Click>,
}

impl Mixer {
    /// Adds a click to be heard.
    pub fn add(&mut self, click: Click) {
        self.clicks.push(click);
    }

    /// Forgets every click, sounding or due.
    pub fn clear(&mut self) {
        self.clicks.clear();
    }

    /// Clicks still to be heard in whole or in part.
    #[must_use]
    pub fn len(&self) -> usize {
        self.clicks.len()
    }

    /// True when nothing is left to be heard.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.clicks.is_empty()
    }

    /// Fills `out`, interleaved left and right samples of the track's frames
    /// `first`, `first + 1`, ... (frame `n` at `n / RATE` s), with the clicks
    /// sounding then, at `volume`, through the soft limit; forgets the clicks
    /// that have ended by the chunk's end.
    pub fn fill(&mut self, first: u64, volume: f64, out: &mut [f32]) {
        if self.clicks.is_empty() {
            out.fill(0.0);
            return;
        }
        let frames = out.len() / 2;
        let rate = f64::from(RATE);
        let start = first as f64 / rate;
        let end = (first + frames as u64) as f64 / rate;
        let mut mix = vec![0.0_f64; 2 * frames];
        for c in &self.clicks {
            if c.at >= end || c.at + CLICK_LENGTH <= start {
                continue;
            }
            let (gl, gr) = c.gains();
            // Only the frames the click covers: the first at or after its start.
            let from = ((c.at - start) * rate).floor().max(0.0) as usize;
            let to = (((c.at + CLICK_LENGTH - start) * rate).ceil() as usize).min(frames);
            for i in from..to {
                // Each frame's time from its number: chunks of any size agree.
                let u = (first + i as u64) as f64 / rate - c.at;
                let v = c.value(u);
                mix[2 * i] += gl * v;
                mix[2 * i + 1] += gr * v;
            }
        }
        for (o, m) in out.iter_mut().zip(&mix) {
            *o = (volume * m).tanh() as f32;
        }
        self.clicks.retain(|c| c.at + CLICK_LENGTH > end);
    }
}

/// Where on the picture's width a point at `x` (pixels) of a `width` picture is
/// heard: -1 at the left edge, 1 at the right.
#[must_use]
pub fn pan(x: f32, width: u32) -> f64 {
    (2.0 * f64::from(x) / f64::from(width.max(1)) - 1.0).clamp(-1.0, 1.0)
}

/// One sample as 16-bit PCM.
#[must_use]
pub fn pcm(v: f32) -> i16 {
    (v.clamp(-1.0, 1.0) * 32767.0).round() as i16
}

#[cfg(test)]
mod tests {
    use super::{Click, Mixer, RATE, Timbre};
    use crate::physics::{Contact, Impact};

    fn steel() -> Timbre {
        // The default asset's balls: steel, 2 cm, 0.263 kg.
        Timbre::new(2.0e11, 0.29, 0.02, 0.263)
    }

    fn ideal(speed: f64) -> Impact {
        Impact {
            t: 0.0,
            pair: 0,
            speed,
            at: (0.0, 0.0),
            contact: None,
        }
    }

    #[test]
    fn an_ideal_impact_sounds_as_the_hertz_contact_it_stands_for() {
        // Steel, 2 cm balls at 0.65 m/s: Hertz's law gives about 2300 N over
        // 0.13 ms (worked by hand in docs/sound.md); 3% allows for the rounding
        // of those figures.
        let (force, tau) = steel().pulse(&ideal(0.65)).unwrap();
        assert!((force / 2330.0 - 1.0).abs() < 0.03, "{force}");
        assert!((tau / 1.33e-4 - 1.0).abs() < 0.03, "{tau}");
        assert!(steel().pulse(&ideal(0.0)).is_none());
    }

    #[test]
    fn harder_impacts_are_louder_and_brighter() {
        let soft = Click::of(&ideal(0.2), &steel(), 0.0, 0.0).unwrap();
        let hard = Click::of(&ideal(1.0), &steel(), 0.0, 0.0).unwrap();
        assert!(
            hard.level > 3.0 * soft.level,
            "{} {}",
            hard.level,
            soft.level
        );
        assert!(hard.pulse < soft.pulse);
    }

    #[test]
    fn a_measured_contact_is_used_as_measured() {
        let mut i = ideal(0.65);
        i.contact = Some(Contact {
            duration: 2e-4,
            peak_force: 1000.0,
            impulse: 0.13,
        });
        assert_eq!(steel().pulse(&i), Some((1000.0, 2e-4)));
    }

    #[test]
    fn a_click_starts_on_the_first_sample_after_its_time_and_fills_by_chunks_as_at_once() {
        let at = 0.012_345_6;
        let click = Click::of(&ideal(0.65), &steel(), at, -0.5).unwrap();
        let whole = {
            let mut m = Mixer::default();
            m.add(click);
            let mut out = vec![0.0; 2 * 4800];
            m.fill(0, 1.0, &mut out);
            out
        };
        let onset = whole.iter().position(|v| v.abs() > 1e-3).unwrap() / 2;
        let exact = at * f64::from(RATE);
        assert!(
            onset as f64 >= exact && (onset as f64) < exact + 1.0,
            "{onset} vs {exact}"
        );
        // Panned left: the left channel is the louder.
        assert!(whole[2 * onset].abs() > whole[2 * onset + 1].abs());
        let mut m = Mixer::default();
        m.add(click);
        let mut chunks = Vec::new();
        for k in 0..10 {
            let mut out = vec![0.0; 2 * 480];
            m.fill(k * 480, 1.0, &mut out);
            chunks.extend(out);
        }
        // The same frame times, as products: the same samples.
        assert_eq!(chunks, whole);
    }

    #[test]
    fn a_mixer_forgets_clicks_once_heard() {
        let mut m = Mixer::default();
        m.add(Click::of(&ideal(0.65), &steel(), 0.0, 0.0).unwrap());
        let mut out = vec![0.0; 2 * 480];
        m.fill(0, 1.0, &mut out);
        assert_eq!(m.len(), 1);
        m.fill(u64::from(RATE), 1.0, &mut out);
        assert!(m.is_empty());
        assert!(out.iter().all(|v| *v == 0.0));
    }
}
