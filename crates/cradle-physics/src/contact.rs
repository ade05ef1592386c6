//! Contacts between neighbouring balls: the gap function whose roots are impacts
//! (`params`, with the rest of the cradle's geometry), the contact normal and
//! levers, and the impulses that resolve them (ideal impacts with restitution).
//!
//! Only neighbours collide: in one plane a ball cannot reach past its neighbour.

use super::params::CradleParams;
pub use super::params::{gap_fn, overlap};

/// Unit contact normal from ball `a` to ball `b = a + 1` and the levers
/// `J = dc/dtheta . n` of each ball (m/rad).
fn normal_and_levers(p: &CradleParams, theta_a: f64, theta_b: f64) -> ((f64, f64), f64, f64) {
    let (sa, ca) = theta_a.sin_cos();
    let (sb, cb) = theta_b.sin_cos();
    let dx = p.spacing() + p.length * (sb - sa);
    let dy = -p.length * (cb - ca);
    let len = dx.hypot(dy);
    let n = (dx / len, dy / len);
    let lever = |s: f64, c: f64| p.length * (c * n.0 + s * n.1);
    (n, lever(sa, ca), lever(sb, cb))
}

/// The levers `J = dc/dtheta . n` (m/rad) of balls `a` and `b = a + 1` along
/// their contact normal: a force `F` pushing them apart gives torques `-F J_a` and
/// `F J_b`.
#[must_use]
pub fn levers(p: &CradleParams, theta_a: f64, theta_b: f64) -> (f64, f64) {
    let (_, ja, jb) = normal_and_levers(p, theta_a, theta_b);
    (ja, jb)
}

/// Normal speed of `b` relative to `a` (m/s): negative while they approach.
#[must_use]
pub fn closing_speed(p: &CradleParams, a: (f64, f64), b: (f64, f64)) -> f64 {
    let (_, ja, jb) = normal_and_levers(p, a.0, b.0);
    jb * b.1 - ja * a.1
}

/// Time derivative of [`gap_fn`] along the motion (m^2/s).
#[must_use]
pub fn gap_rate(p: &CradleParams, a: (f64, f64), b: (f64, f64)) -> f64 {
    let (ca, cb) = (p.centre(0, a.0), p.centre(1, b.0));
    let va = (p.length * a.0.cos() * a.1, p.length * a.0.sin() * a.1);
    let vb = (p.length * b.0.cos() * b.1, p.length * b.0.sin() * b.1);
    2.0 * ((cb.0 - ca.0) * (vb.0 - va.0) + (cb.1 - ca.1) * (vb.1 - va.1))
}

impl Resolution {
    /// Closing speeds below this (m/s) are round-off, not approach: 1e-12 of the
    /// rest speed.
    #[must_use]
    pub fn round_off(&self) -> f64 {
        1e-12 * self.rest_speed
    }
}

/// Settings of one contact resolution.
#[derive(Debug, Clone, Copy)]
pub struct Resolution {
    /// Restitution 0..=1.
    pub restitution: f64,
    /// Closing speeds below this (m/s) are resting contact: restitution 0 if < 1.
    pub rest_speed: f64,
    /// Pairs whose surfaces are closer than this (m) count as touching.
    pub touch: f64,
}

/// Applies the impulse of one impact between balls `a` and `a + 1`. Returns the
/// range of balls it changed and whether it was an impact (closing faster than the
/// rest speed) rather than resting contact.
pub fn impact(
    p: &CradleParams,
    r: &Resolution,
    theta: &mut [f64],
    omega: &mut [f64],
    a: usize,
) -> (std::ops::RangeInclusive<usize>, bool) {
    let b = a + 1;
    // Touching balls (gap 0) at angles equal to round-off collide at equal angles:
    // put the faster on the slower's angle (a shift of the root-finding error, ~1e-16
    // rad) so that balls between stay exactly at rest and outgoing ones move alike.
    if p.gap == 0.0 && (theta[a] - theta[b]).abs() < 1e-9 {
        let (moved, onto) = if omega[a].abs() > omega[b].abs() {
            (a, b)
        } else {
            (b, a)
        };
        snap(p, theta, omega, moved, onto);
    }
    let vn = closing_speed(p, (theta[a], omega[a]), (theta[b], omega[b]));
    let counted = -vn >= r.rest_speed;
    let e = if counted || r.restitution == 1.0 {
        r.restitution
    } else {
        0.0
    };
    if theta[a] == theta[b] && p.gap == 0.0 {
        // Equal levers: the impulse is symmetric; write it so that e = 1 swaps and
        // e = 0 equalises exactly.
        if e == 1.0 {
            omega.swap(a, b);
        } else if e == 0.0 {
            return (rest_block(p, r, theta, omega, a), counted);
        } else {
            let mean = 0.5 * (omega[a] + omega[b]);
            let half = 0.5 * e * (omega[b] - omega[a]);
            omega[a] = mean + half;
            omega[b] = mean - half;
        }
    } else {
        let (_, ja, jb) = normal_and_levers(p, theta[a], theta[b]);
        // Impulse lambda (per unit inertia) making the closing speed -e vn.
        let lambda = -(1.0 + e) * vn / (ja * ja + jb * jb);
        omega[a] -= lambda * ja;
        omega[b] += lambda * jb;
    }
    (a..=b, counted)
}

/// Puts ball `moved` on ball `onto`'s angle and rescales its speed so that its own
/// energy is unchanged: the shift is the root-finding error, but with short strings
/// and large angles the potential energy it moves would otherwise show.
fn snap(p: &CradleParams, theta: &mut [f64], omega: &mut [f64], moved: usize, onto: usize) {
    let (old, new) = (theta[moved], theta[onto]);
    let (so, sn) = ((0.5 * old).sin(), (0.5 * new).sin());
    // I w'^2 / 2 + 2 m g L sn^2 = I w^2 / 2 + 2 m g L so^2.
    let gain = 4.0 * p.mass * p.gravity * p.length / p.inertia() * (so - sn) * (so + sn);
    let w2 = omega[moved] * omega[moved] + gain;
    omega[moved] = omega[moved].signum() * w2.max(0.0).sqrt();
    theta[moved] = new;
}

/// Resting contact in a touching chain (gap 0): every ball touching `a` at the same
/// angle and moving within the rest speed of it joins one block moving at the mean
/// angular velocity, exactly the same for each, as a perfectly inelastic chain
/// ends. Pairwise averaging would instead leave differences of an ulp that collide
/// again and again at one instant. Returns the block.
fn rest_block(
    p: &CradleParams,
    r: &Resolution,
    theta: &[f64],
    omega: &mut [f64],
    a: usize,
) -> std::ops::RangeInclusive<usize> {
    let slow = r.rest_speed / p.length;
    let joins = |i: usize, j: usize| theta[i] == theta[j] && (omega[i] - omega[j]).abs() < slow;
    let (mut lo, mut hi) = (a, a + 1);
    while lo > 0 && joins(lo - 1, lo) {
        lo -= 1;
    }
    while hi + 1 < omega.len() && joins(hi, hi + 1) {
        hi += 1;
    }
    let mean = omega[lo..=hi].iter().sum::<f64>() / (hi - lo + 1) as f64;
    omega[lo..=hi].fill(mean);
    lo..=hi
}

/// What one resolution did: balls whose state changed, and pairs whose last
/// impulse was a resting contact (slower than the rest speed).
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Per ball: its angular velocity (or angle, when snapped) changed.
    pub changed: Vec<bool>,
    /// Per ball: changed by an impact, not only by resting contact.
    pub kicked: Vec<bool>,
    /// Per pair `(a, a+1)`: `Some(true)` resting contact, `Some(false)` impact, `None` untouched.
    pub resting: Vec<Option<bool>>,
    /// Impacts (resting contacts excluded).
    pub impacts: u64,
    /// Each impact in the order resolved: the pair and how fast it closed (m/s).
    pub hits: Vec<(usize, f64)>,
}

/// Resolves impact `first` (between balls `first` and `first + 1`), then every
/// touching pair that still approaches, fastest first, until none does: a striker
/// passes through a touching chain pair by pair.
pub fn resolve(
    p: &CradleParams,
    r: &Resolution,
    theta: &mut [f64],
    omega: &mut [f64],
    first: usize,
) -> Outcome {
    let n = theta.len();
    let mut out = Outcome {
        changed: vec![false; n],
        kicked: vec![false; n],
        resting: vec![None; n.saturating_sub(1)],
        impacts: 0,
        hits: Vec::new(),
    };
    let hit = |a: usize, theta: &mut [f64], omega: &mut [f64], out: &mut Outcome| {
        let vn = closing_speed(p, (theta[a], omega[a]), (theta[a + 1], omega[a + 1]));
        let (balls, counted) = impact(p, r, theta, omega, a);
        out.impacts += u64::from(counted);
        if counted {
            out.hits.push((a, -vn));
        }
        out.resting[a] = Some(!counted);
        for i in balls.clone() {
            out.changed[i] = true;
            out.kicked[i] |= counted;
        }
        balls
    };
    // A root at round-off level can belong to a pair that is not approaching: no
    // impulse then (one would pull the balls together), only resting contact.
    let vn = closing_speed(
        p,
        (theta[first], omega[first]),
        (theta[first + 1], omega[first + 1]),
    );
    if vn < -r.round_off() {
        hit(first, theta, omega, &mut out);
    } else {
        out.resting[first] = Some(true);
    }
    // Each pass removes one approaching pair; a chain of n balls with k strikers
    // needs about k (n - k) passes, far below this bound, which only guards the
    // geometric tail of restitution < 1.
    let max_passes = 8 * n * n + 16;
    let touch_h = r.touch * (4.0 * p.radius + r.touch);
    // Each pair's closing speed where it touches (`None`: apart). An impact
    // changes only the balls it returns, so only the pairs beside them are
    // worked out again: the same values, without each of a chain's k (n - k)
    // passes working out every pair (some 20 ms for a 200-ball row's impact).
    let speed = |a: usize, theta: &[f64], omega: &[f64]| {
        if gap_fn(p, theta[a], theta[a + 1]) > touch_h {
            None
        } else {
            Some(closing_speed(
                p,
                (theta[a], omega[a]),
                (theta[a + 1], omega[a + 1]),
            ))
        }
    };
    let pairs = n.saturating_sub(1);
    let mut speeds: Vec<Option<f64>> = (0..pairs).map(|a| speed(a, theta, omega)).collect();
    for _ in 0..max_passes {
        let mut worst: Option<(usize, f64)> = None;
        for (a, &vn) in speeds.iter().enumerate() {
            if let Some(vn) = vn
                && vn < -r.round_off()
                && worst.is_none_or(|(_, w)| vn < w)
            {
                worst = Some((a, vn));
            }
        }
        let Some((a, _)) = worst else {
            return out;
        };
        let balls = hit(a, theta, omega, &mut out);
        let (lo, hi) = (
            balls.start().saturating_sub(1),
            (*balls.end()).min(pairs - 1),
        );
        for (j, s) in (lo..=hi).zip(&mut speeds[lo..=hi]) {
            *s = speed(j, theta, omega);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{Outcome, Resolution, closing_speed, impact, resolve};
    use crate::params::{CradleParams, gap_fn};

    /// `resolve` as its rule says, every touching pair's closing speed worked
    /// out afresh on every pass: what the kept speeds must reproduce.
    fn resolve_afresh(
        p: &CradleParams,
        r: &Resolution,
        theta: &mut [f64],
        omega: &mut [f64],
        first: usize,
    ) -> (Vec<usize>, u64) {
        let n = theta.len();
        let touch_h = r.touch * (4.0 * p.radius + r.touch);
        let mut order = Vec::new();
        let mut impacts = 0;
        let mut a = Some(first);
        // The first pair, then at most as many passes as `resolve` makes.
        for _ in 0..=8 * n * n + 16 {
            let Some(pair) = a else {
                break;
            };
            let vn = closing_speed(
                p,
                (theta[pair], omega[pair]),
                (theta[pair + 1], omega[pair + 1]),
            );
            if pair != first || !order.is_empty() || vn < -r.round_off() {
                impacts += u64::from(impact(p, r, theta, omega, pair).1);
                order.push(pair);
            }
            a = None;
            let mut worst = f64::INFINITY;
            for k in 0..n - 1 {
                if gap_fn(p, theta[k], theta[k + 1]) > touch_h {
                    continue;
                }
                let vn = closing_speed(p, (theta[k], omega[k]), (theta[k + 1], omega[k + 1]));
                if vn < -r.round_off() && vn < worst {
                    (a, worst) = (Some(k), vn);
                }
            }
        }
        (order, impacts)
    }

    #[test]
    fn a_strike_through_a_touching_row_resolves_as_working_out_every_pair_each_pass() {
        for (n, k, e) in [
            (200, 20, 1.0),
            (40, 7, 0.93),
            (25, 5, 0.5),
            (12, 3, 0.0),
            (5, 2, 1.0),
        ] {
            let p = CradleParams {
                balls: n,
                radius: 0.02,
                mass: 0.26,
                length: 0.16,
                gap: 0.0,
                gravity: 9.81,
                restitution: e,
                hertz: None,
                dissipation: 0.0,
                drag: 0.0,
            };
            let r = Resolution {
                restitution: e,
                rest_speed: 1e-9,
                touch: 2e-11,
            };
            // The k strikers at the bottom, moving right at 1 rad/s (their
            // angular speeds a hair apart, as a swing leaves them); the row
            // at rest, all touching.
            let mut theta = vec![0.0; n];
            let mut omega: Vec<f64> = (0..n)
                .map(|i| if i < k { 1.0 + 1e-12 * i as f64 } else { 0.0 })
                .collect();
            let (mut th, mut om) = (theta.clone(), omega.clone());
            let out: Outcome = resolve(&p, &r, &mut theta, &mut omega, k - 1);
            let (order, impacts) = resolve_afresh(&p, &r, &mut th, &mut om, k - 1);
            // The same state to the bit, and the same impacts in the same order.
            assert_eq!((theta, omega), (th, om), "{n} balls, {k} lifted, e = {e}");
            assert_eq!(out.impacts, impacts, "{n} balls, {k} lifted, e = {e}");
            let hits: Vec<usize> = out.hits.iter().map(|&(a, _)| a).collect();
            let counted: Vec<usize> = order.into_iter().filter(|a| hits.contains(a)).collect();
            assert!(hits.iter().all(|a| counted.contains(a)));
            // An elastic strike of k balls passes on through k (n - k) impacts.
            if e == 1.0 {
                assert_eq!(out.impacts, (k * (n - k)) as u64, "{n} balls, {k} lifted");
            }
        }
    }
}
