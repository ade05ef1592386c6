//! The ranges of the keys the control panel edits, in one place: validation
//! refuses values outside them, and the panel's sliders span them whole, so
//! opening the panel never moves a value the config accepted.

use super::{MAX_ANGLE_DEG, MAX_BALLS};
use std::ops::RangeInclusive;

/// `cradle.balls`.
pub const BALLS: RangeInclusive<usize> = 1..=MAX_BALLS;
/// `start.angle_deg` (degrees).
pub const ANGLE_DEG: RangeInclusive<f64> = 0.0..=MAX_ANGLE_DEG;
/// `cradle.gap` (m).
pub const GAP: RangeInclusive<f64> = 0.0..=10.0;
/// `contact.restitution`.
pub const RESTITUTION: RangeInclusive<f64> = 0.0..=1.0;
/// `contact.dissipation` (s); a cradle takes at most a tenth of its shortest
/// contact besides (`Config::dissipation_limit`).
pub const DISSIPATION: RangeInclusive<f64> = 0.0..=1e-3;
/// `cradle.air_density` (kg/m^3).
pub const AIR_DENSITY: RangeInclusive<f64> = 0.0..=100.0;
/// `sound.volume`.
pub const VOLUME: RangeInclusive<f64> = 0.0..=1.0;
/// `render.samples`.
pub const SAMPLES: RangeInclusive<u32> = 1..=64;
