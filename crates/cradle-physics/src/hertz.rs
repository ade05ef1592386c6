//! Hertz contact: soft elastic spheres pressing with `F = k delta^1.5`, integrated
//! with adaptive Dormand-Prince 5(4) steps through the ~0.1 ms a contact lasts.
//!
//! A contact phase starts when two balls meet (found by the engines' gap roots, as
//! for ideal impacts) and ends when no pair overlaps and no touching pair
//! approaches. During it the whole row is one system: every ball swings under
//! gravity and every overlapping pair pushes along its line of centres. The
//! potential `2/5 k delta^2.5` makes the system conservative, so energy and, along
//! the contact, momentum are kept to the integrator's tolerance. With a
//! dissipative constant (`CradleParams::dissipation`) the contacts are
//! viscoelastic and lose energy, booked in [`PhaseEnd::lost`] (forces in `row`).
//!
//! The step sequence depends only on the phase's start state, never on when the
//! state is asked for: a state inside a phase is one extra step from the step
//! point before it.

use super::contact;
use super::dopri;
use super::impacts::{ImpactLog, Watch};
use super::params::CradleParams;
use super::row::Row;

/// Local error per step, as a fraction of the ball radius (positions) and of the
/// fastest speed at the phase start (velocities). 1e-13 keeps the energy error of
/// a whole contact below 1e-11 relative (measured by `tests/physics.rs`), well under
/// the 1e-9 asked of it, at ~100 steps per contact.
pub(crate) const TOL: f64 = 1e-13;

/// A phase that has not separated after this many steps is cut there and goes on
/// as a new phase: it bounds the work of a query inside a long contact.
const SEGMENT_STEPS: usize = 20_000;

/// Hertz stiffness `k = 4/3 E* sqrt(R*)` (N/m^1.5) of two equal spheres of radius
/// `r` (m): `E* = E / (2 (1 - nu^2))`, `R* = r / 2`.
#[must_use]
pub fn stiffness(youngs_modulus: f64, poisson_ratio: f64, radius: f64) -> f64 {
    let e_star = youngs_modulus / (2.0 * (1.0 - poisson_ratio * poisson_ratio));
    4.0 / 3.0 * e_star * (0.5 * radius).sqrt()
}

/// How long (s) a Hertz contact of stiffness `k` (N/m^1.5) between bodies of
/// reduced mass `m` (kg) lasts when they meet at speed `v` (m/s): `2.94
/// delta_max / v`, with the deepest overlap `delta_max = (5 m v^2 / (4 k))^(2/5)`
/// (Johnson, Contact Mechanics, 11.2). Shorter the faster they meet.
#[must_use]
pub fn contact_time(k: f64, m: f64, v: f64) -> f64 {
    let deepest = (1.25 * m * v * v / k).powf(0.4);
    2.94 * deepest / v
}

/// How a phase (or a segment of one) ended.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseEnd {
    /// Time of the last step (s).
    pub t: f64,
    /// Angles (rad).
    pub theta: Vec<f64>,
    /// Angular velocities (rad/s).
    pub omega: Vec<f64>,
    /// True when every pair has come apart; false when cut by the stop time or
    /// the segment length.
    pub separated: bool,
    /// Pairs that came into contact during it (onsets of overlap).
    pub contacts: u64,
    /// Energy lost during it in contacts and to air drag (J): 0 without
    /// dissipation.
    pub lost: [f64; 2],
}

/// Where a phase reports its contacts: the watch that follows them across
/// segments, the log they go to, and the time the phase's times count from (s).
pub(crate) struct Report<'a> {
    pub(crate) watch: &'a mut Watch,
    pub(crate) log: &'a mut ImpactLog,
    pub(crate) epoch: f64,
}

/// Integrates a contact phase from `(theta, omega)` at `t0` until the balls come
/// apart, the step count reaches a segment, or `stop` (s) is reached; at `stop`
/// the state is one shortened step from the last step point, and the step
/// sequence is the one a run without `stop` takes.
///
/// `k` is the Hertz stiffness (N/m^1.5).
#[must_use]
pub fn run_phase(
    p: &CradleParams,
    k: f64,
    t0: f64,
    theta: &[f64],
    omega: &[f64],
    stop: f64,
) -> PhaseEnd {
    run_reported(p, k, (t0, theta, omega), stop, None)
}

/// [`run_phase`], and with a `report` each contact that ends in the phase goes
/// to its log (the steps are the same either way).
pub(crate) fn run_reported(
    p: &CradleParams,
    k: f64,
    (t0, theta, omega): (f64, &[f64], &[f64]),
    stop: f64,
    mut report: Option<Report<'_>>,
) -> PhaseEnd {
    let n = theta.len();
    let impulses = report.as_ref().is_some_and(|r| r.log.recording());
    let sys = Row::new(p, k, n).with_impulses(impulses);
    let mut y = sys.state(theta, omega);
    // Error scales: positions to TOL radii, speeds to TOL of the fastest ball, or of
    // the speed gravity gives over the contact time when everything is at rest.
    let w_max = omega.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
    let w_floor = 1e-6 * p.w0() * p.radius / p.length;
    let mut scale = vec![TOL * p.radius / p.length; sys.len()];
    scale[n..2 * n].fill(TOL * w_max.max(w_floor));
    // The energy lost to TOL of the energy in play: the viscoelastic force grows
    // as sqrt(overlap) from a contact's start, which the state's own error
    // control alone leaves to the coarser steps there.
    let in_play = 0.5 * p.inertia() * w_max.max(w_floor).powi(2);
    sys.scale_extra(&mut scale, TOL * in_play);
    // First step: a hundredth of the time to close one radius's thousandth.
    let mut h = (1e-5 * p.radius / (p.length * w_max.max(w_floor))).min(1e-3 / p.w0());
    let mut t = t0;
    let mut k_buf: [Vec<f64>; 7] = std::array::from_fn(|_| vec![0.0; sys.len()]);
    let overlapping = |y: &[f64], a: usize| sys.overlap(&y[..n], a) > 0.0;
    let mut touching: Vec<bool> = (0..n.saturating_sub(1))
        .map(|a| overlapping(&y, a))
        .collect();
    let mut contacts = 0;
    let end = |t: f64, y: &[f64], separated: bool, contacts: u64| PhaseEnd {
        t,
        theta: y[..n].to_vec(),
        omega: y[n..2 * n].to_vec(),
        separated,
        contacts,
        lost: sys.lost(y),
    };
    let deriv = |y: &[f64], out: &mut [f64]| sys.deriv(y, out);
    if let Some(r) = report.as_mut() {
        let curves = r.log.recording_courses();
        r.watch.begin(&sys, r.epoch + t0, &y, curves);
    }
    let mut steps = 0;
    loop {
        let (y1, err) = dopri::step(&deriv, &y, h, &scale, &mut k_buf);
        let floor = min_step(p, t);
        if (err > 1.0 || !err.is_finite()) && h > floor {
            // A NaN factor leaves the floor (`max` ignores NaN).
            h = (h * (0.9 * err.powf(-0.2)).clamp(0.1, 0.9)).max(floor);
            continue;
        }
        if err > 1.0 {
            // The error is not met even at the shortest step: take it all the
            // same, so that the phase always advances (it never ends where it
            // began, to be started again from there for ever).
            warn_forced(t, err);
        }
        if !y1.iter().all(|v| v.is_finite()) {
            tracing::warn!("contact state not finite at t = {t} s; contact ended");
            return end(t, &y, true, contacts);
        }
        if t + h > stop {
            let (ys, _) = dopri::step(&deriv, &y, stop - t, &scale, &mut k_buf);
            // A fixed-step engine goes on from here: its contacts see this point.
            if let Some(r) = report.as_mut() {
                r.watch.step(&sys, r.epoch + stop, &ys, r.log);
            }
            return end(stop, &ys, false, contacts);
        }
        if t + h == t {
            // The step is below f64's resolution of time here: nothing could ever
            // advance. The ranges of the config keep this from happening; should
            // it, the contact ends here rather than the program hanging.
            tracing::warn!(
                "contact step {h:e} s is below the resolution of t = {t} s; contact ended"
            );
            return end(t, &y, true, contacts);
        }
        t += h;
        y = y1;
        steps += 1;
        if let Some(r) = report.as_mut() {
            r.watch.step(&sys, r.epoch + t, &y, r.log);
        }
        for (a, was) in touching.iter_mut().enumerate() {
            let now = overlapping(&y, a);
            contacts += u64::from(now && !*was);
            *was = now;
        }
        if separated(p, &y, n) {
            return end(t, &y, true, contacts);
        }
        if steps >= SEGMENT_STEPS {
            return end(t, &y, false, contacts);
        }
        h *= (0.9 * err.max(1e-10).powf(-0.2)).min(5.0);
    }
}

/// The shortest step a phase takes at time `t` (s): 64 ulps of `t`, or of the
/// pendulum's time scale `1 / w0` near t = 0. A step the error control would
/// cut shorter is taken at this length, error or not.
fn min_step(p: &CradleParams, t: f64) -> f64 {
    64.0 * f64::EPSILON * t.abs().max(1.0 / p.w0())
}

/// Says once per process that a contact step was taken above its error bound.
fn warn_forced(t: f64, err: f64) {
    static SAID: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
    if !SAID.swap(true, std::sync::atomic::Ordering::Relaxed) {
        tracing::warn!(
            "a contact step at t = {t} s met its error bound only to {err:.1e} times it \
             (the shortest step f64 can take there); the contact goes on"
        );
    }
}

/// True when no pair overlaps and no pair closer than a billionth of a radius
/// approaches (the phase starts at such a pair: the gap root's last positive time).
fn separated(p: &CradleParams, y: &[f64], n: usize) -> bool {
    let (theta, omega) = y.split_at(n);
    let touch_h = 4e-9 * p.radius * p.radius;
    (0..n.saturating_sub(1)).all(|a| {
        let h = contact::gap_fn(p, theta[a], theta[a + 1]);
        h >= 0.0
            && (h > touch_h
                || contact::closing_speed(p, (theta[a], omega[a]), (theta[a + 1], omega[a + 1]))
                    >= 0.0)
    })
}
