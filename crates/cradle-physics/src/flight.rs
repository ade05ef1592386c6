//! Closed-form flight of one pendulum between impacts: the exact engine evaluates
//! these at any time in O(1), which is what makes the physics frame-rate independent.
//!
//! With `w0` the small-angle angular frequency, energy conservation gives
//! `(omega / 2 w0)^2 + sin^2(theta / 2) = k^2`, constant along a flight.
//! - `k < 1`, libration: `sin(theta/2) = k sn(u | k^2)`, `omega = 2 k w0 cn(u)`,
//!   `u = u0 + w0 (t - t0)`; period `4 K(k^2) / w0`.
//! - `k > 1`, rotation over the top: `theta = 2 am(v | 1/k^2)`,
//!   `omega = 2 sigma k w0 dn(v)`, `v = v0 + sigma k w0 (t - t0)`.
//! - `k = 0`: at rest at the bottom.

use super::elliptic::{ellip_f, ellip_k, phase_of, sncndn_k};
use std::f64::consts::{PI, TAU};

/// Parameters closer to 1 than this are moved off the separatrix (`K` is infinite
/// there); the change of the motion is below 1e-15 rad over a period.
const SEPARATRIX_GUARD: f64 = 1e-15;

/// How a flight moves: the constants of its closed form.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Motion {
    /// Hanging still at `centre` (a multiple of 2 pi).
    Rest,
    /// Swinging about `centre` with modulus `k`, parameter `m = k^2`, phase `u0` at
    /// `t0`, quarter period `kk = K(m)` in phase.
    Libration { k: f64, m: f64, u0: f64, kk: f64 },
    /// Going over the top: parameter `m = 1/k^2`, phase `v0` at `t0`, direction
    /// `sigma`, `kk = K(m)`.
    Rotation {
        k: f64,
        m: f64,
        v0: f64,
        sigma: f64,
        kk: f64,
    },
}

/// One pendulum's exact motion from `(theta0, omega0)` at time `t0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flight {
    t0: f64,
    w0: f64,
    centre: f64,
    motion: Motion,
}

impl Flight {
    /// The same flight with its times counted from `by` (s) later: its start
    /// moves back by `by` (the engine's epoch moved forward).
    pub(crate) fn shift(&mut self, by: f64) {
        self.t0 -= by;
    }

    /// The flight through angle `theta` (rad) with angular velocity `omega` (rad/s) at
    /// time `t0` (s), for small-angle angular frequency `w0` (rad/s, > 0).
    #[must_use]
    pub fn new(t0: f64, theta: f64, omega: f64, w0: f64) -> Self {
        let centre = TAU * (theta / TAU).round();
        let rel = theta - centre; // in [-pi, pi]
        let s = (0.5 * rel).sin();
        let c = omega / (2.0 * w0);
        let k2 = s * s + c * c;
        let motion = if k2 == 0.0 {
            Motion::Rest
        } else if k2 < 1.0 - SEPARATRIX_GUARD {
            let k = k2.sqrt();
            Motion::Libration {
                k,
                m: k2,
                u0: phase_of(s / k, c / k, k2),
                kk: ellip_k(k2),
            }
        } else {
            let k = k2.sqrt().max(1.0 + SEPARATRIX_GUARD);
            let m = 1.0 / (k * k);
            Motion::Rotation {
                k,
                m,
                v0: ellip_f(0.5 * rel, m),
                sigma: if omega < 0.0 { -1.0 } else { 1.0 },
                kk: ellip_k(m),
            }
        };
        Self {
            t0,
            w0,
            centre,
            motion,
        }
    }

    /// Angle (rad) and angular velocity (rad/s) at time `t`.
    #[must_use]
    pub fn state_at(&self, t: f64) -> (f64, f64) {
        let dt = t - self.t0;
        match self.motion {
            Motion::Rest => (self.centre, 0.0),
            Motion::Libration { k, m, u0, kk } => {
                let (sn, cn, _) = sncndn_k(u0 + self.w0 * dt, m, kk);
                // k sn can exceed 1 by an ulp at the turning points; asin would give NaN.
                let theta = 2.0 * (k * sn).clamp(-1.0, 1.0).asin();
                (self.centre + theta, 2.0 * k * self.w0 * cn)
            }
            Motion::Rotation {
                k,
                m,
                v0,
                sigma,
                kk,
            } => {
                let v = v0 + sigma * k * self.w0 * dt;
                let half_period = 2.0 * kk;
                let turns = (v / half_period).round();
                let (sn, cn, dn) = sncndn_k(v - turns * half_period, m, kk);
                let am = sn.atan2(cn) + turns * PI;
                (self.centre + 2.0 * am, 2.0 * sigma * k * self.w0 * dn)
            }
        }
    }

    /// True when the pendulum hangs still.
    #[must_use]
    pub fn is_rest(&self) -> bool {
        self.motion == Motion::Rest
    }

    /// Time (s) of one full swing (libration) or one full turn (rotation); the
    /// small-angle period `2 pi / w0` at rest.
    #[must_use]
    pub fn period(&self) -> f64 {
        match self.motion {
            Motion::Rest => TAU / self.w0,
            Motion::Libration { kk, .. } => 4.0 * kk / self.w0,
            Motion::Rotation { k, kk, .. } => 2.0 * kk / (k * self.w0),
        }
    }

    /// The flight's modulus `k`: `sin(theta_max / 2)` for a swing, 0 at rest.
    #[must_use]
    pub fn modulus(&self) -> f64 {
        match self.motion {
            Motion::Rest => 0.0,
            Motion::Libration { k, .. } | Motion::Rotation { k, .. } => k,
        }
    }
}

/// Period of a pendulum released from rest at `amplitude` (rad, < pi), relative to
/// the small-angle period: `2 K(sin^2(amplitude/2)) / pi`.
#[must_use]
pub fn period_ratio(amplitude: f64) -> f64 {
    let k = (0.5 * amplitude).sin();
    2.0 * ellip_k(k * k) / PI
}
