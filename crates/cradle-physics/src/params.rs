//! The physical parameters of a cradle and the quantities derived from them
//! (pivot spacing, moment of inertia, natural frequency, energy, ball centres,
//! the gap and overlap of neighbours).

use serde::{Deserialize, Serialize};

/// Below this fraction of the fastest speed the cradle starts with, an impact with
/// restitution < 1 is treated as resting contact (restitution 0): without it a
/// chain of touching balls would collide infinitely often in finite time (Zeno).
pub const REST_FRACTION: f64 = 1e-6;

/// Which solver advances the cradle between impacts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Integrator {
    /// Closed-form flight (Jacobi elliptic functions) and root-found impacts.
    #[default]
    Exact,
    /// Semi-implicit (symplectic) Euler, order 1.
    Euler,
    /// Stormer-Verlet (velocity form), order 2.
    Verlet,
    /// Classic Runge-Kutta, order 4.
    Rk4,
    /// Yoshida's 4th-order composition of Verlet steps.
    Yoshida4,
}

impl Integrator {
    /// Every integrator, in the order the CLI lists them.
    pub const ALL: [Self; 5] = [
        Self::Exact,
        Self::Euler,
        Self::Verlet,
        Self::Rk4,
        Self::Yoshida4,
    ];

    /// The name used in configs, flags and JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Exact => "exact",
            Self::Euler => "euler",
            Self::Verlet => "verlet",
            Self::Rk4 => "rk4",
            Self::Yoshida4 => "yoshida4",
        }
    }
}

/// Everything the physics needs to know about a cradle (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CradleParams {
    /// Number of balls.
    pub balls: usize,
    /// Ball radius (m).
    pub radius: f64,
    /// Ball mass (kg).
    pub mass: f64,
    /// Pivot to ball centre (m).
    pub length: f64,
    /// Gap between neighbouring balls at rest (m).
    pub gap: f64,
    /// Gravitational acceleration (m/s^2).
    pub gravity: f64,
    /// Coefficient of restitution of ideal impacts, 0..=1.
    pub restitution: f64,
    /// Hertz contact stiffness `k` (N/m^1.5) of soft balls, or `None` for ideal
    /// impacts ([`super::hertz`]).
    pub hertz: Option<f64>,
    /// Dissipative constant `A` (s) of viscoelastic Hertz contact (`row`): 0 for
    /// elastic contact. Used with `hertz` only.
    pub dissipation: f64,
    /// Quadratic air drag `c = rho C_d pi r^2 / 2` (kg/m): a ball's centre moving at
    /// `v` feels `c v^2` against its motion. 0 for none; used with `hertz` and
    /// the exact engine only, whose flights are then integrated ([`super::damped`]).
    pub drag: f64,
}

impl CradleParams {
    /// The drag constant `c` (kg/m) of a sphere of radius `radius` (m) with drag
    /// coefficient `cd` in air of density `rho` (kg/m^3): `rho cd pi r^2 / 2`.
    #[must_use]
    pub fn drag_of(rho: f64, cd: f64, radius: f64) -> f64 {
        0.5 * rho * cd * std::f64::consts::PI * radius * radius
    }

    /// True when the cradle loses energy through viscoelastic contacts or drag.
    #[must_use]
    pub fn dissipative(&self) -> bool {
        self.hertz.is_some() && (self.dissipation > 0.0 || self.drag > 0.0)
    }

    /// Distance between neighbouring pivots (m): `2r + gap`.
    #[must_use]
    pub fn spacing(&self) -> f64 {
        2.0 * self.radius + self.gap
    }

    /// Moment of inertia about the pivot of a solid sphere on a rigid V of strings
    /// (kg m^2): `m (L^2 + 2 r^2 / 5)`.
    #[must_use]
    pub fn inertia(&self) -> f64 {
        self.mass * (self.length * self.length + 0.4 * self.radius * self.radius)
    }

    /// Small-angle angular frequency (rad/s): `sqrt(g L / (L^2 + 2 r^2 / 5))`.
    #[must_use]
    pub fn w0(&self) -> f64 {
        (self.gravity * self.length / (self.length * self.length + 0.4 * self.radius * self.radius))
            .sqrt()
    }

    /// Energy of one ball (J): `I omega^2 / 2 + m g L (1 - cos theta)`, with
    /// `1 - cos theta` written as `2 sin^2(theta/2)` to keep its digits near 0.
    #[must_use]
    pub fn ball_energy(&self, theta: f64, omega: f64) -> f64 {
        let s = (0.5 * theta).sin();
        0.5 * self.inertia() * omega * omega + 2.0 * self.mass * self.gravity * self.length * s * s
    }

    /// Horizontal momentum of one ball (kg m/s): its mass times its centre's
    /// horizontal speed, `m L cos(theta) omega`.
    #[must_use]
    pub fn ball_momentum(&self, theta: f64, omega: f64) -> f64 {
        self.mass * self.length * theta.cos() * omega
    }

    /// Total horizontal momentum of the balls (kg m/s): what an impact passes
    /// on and the strings change as the balls swing.
    #[must_use]
    pub fn momentum(&self, theta: &[f64], omega: &[f64]) -> f64 {
        theta
            .iter()
            .zip(omega)
            .map(|(&t, &w)| self.ball_momentum(t, w))
            .sum()
    }

    /// Total energy of the cradle (J): the balls' energies plus, with Hertz contact,
    /// the elastic energy `2/5 k delta^2.5` of every overlapping pair.
    #[must_use]
    pub fn energy(&self, theta: &[f64], omega: &[f64]) -> f64 {
        let balls: f64 = theta
            .iter()
            .zip(omega)
            .map(|(&t, &w)| self.ball_energy(t, w))
            .sum();
        let Some(k) = self.hertz else {
            return balls;
        };
        let elastic: f64 = theta
            .windows(2)
            .map(|w| overlap(self, w[0], w[1]).max(0.0))
            .map(|d| 0.4 * k * d * d * d.sqrt())
            .sum();
        balls + elastic
    }

    /// Centre of ball `i` in the swing plane, relative to ball 0's pivot (m):
    /// `(i d + L sin theta, -L cos theta)`.
    #[must_use]
    pub fn centre(&self, i: usize, theta: f64) -> (f64, f64) {
        let (s, c) = theta.sin_cos();
        (
            i as f64 * self.spacing() + self.length * s,
            -self.length * c,
        )
    }

    /// Speed (m/s) of a ball's centre at the bottom after release from `angle` (rad).
    #[must_use]
    pub fn release_speed(&self, angle: f64) -> f64 {
        2.0 * self.length * self.w0() * (0.5 * angle).sin().abs()
    }
}

/// The starting state: the `lift` leftmost balls pulled to `-angle`, all at rest.
#[must_use]
pub fn lifted_start(balls: usize, lift: usize, angle: f64) -> (Vec<f64>, Vec<f64>) {
    let theta = (0..balls)
        .map(|i| if i < lift { -angle } else { 0.0 })
        .collect();
    (theta, vec![0.0; balls])
}

/// The largest `|theta|` (rad) any ball can reach from [`lifted_start`]'s state,
/// by energy alone.
///
/// The exact engine never adds energy (a tested property), and no ball can hold
/// more than all of it: with `lift` balls at `angle`, no ball passes
/// `2 asin(sqrt(lift) sin(angle/2))` (exactly `angle` for one ball), and `pi`
/// when the energy could carry one over the top. Fixed-step integrators can gain
/// energy, so for them the bound is `pi`.
#[must_use]
pub fn swing_bound(integrator: Integrator, lift: usize, angle: f64) -> f64 {
    if integrator != Integrator::Exact {
        return std::f64::consts::PI;
    }
    let s = (lift as f64).sqrt() * (0.5 * angle).sin();
    2.0 * s.min(1.0).asin()
}

/// The contact test of neighbours `a` (left) and `b = a + 1`: `h = |c_b - c_a|^2 - 4 r^2`,
/// which has the sign of the gap between the balls' surfaces. Written with
/// `delta = theta_b - theta_a` and `mean = (theta_a + theta_b) / 2` as
/// `gap (gap + 4 r) + 4 L sin(delta/2) (d cos(mean) + L sin(delta/2))`, so that it is
/// exactly 0 for touching balls (`gap = 0`) at equal angles, as a resting chain is.
#[must_use]
pub fn gap_fn(p: &CradleParams, theta_a: f64, theta_b: f64) -> f64 {
    let s = (0.5 * (theta_b - theta_a)).sin();
    let mean = 0.5 * (theta_a + theta_b);
    p.gap * (p.gap + 4.0 * p.radius)
        + 4.0 * p.length * s * (p.spacing() * mean.cos() + p.length * s)
}

/// Overlap of neighbours at `theta_a`, `theta_b` (m), positive when the spheres
/// interpenetrate: `2r - |c_b - c_a|`, written from the gap function without
/// cancellation.
#[must_use]
pub fn overlap(p: &CradleParams, theta_a: f64, theta_b: f64) -> f64 {
    let h = gap_fn(p, theta_a, theta_b);
    let r2 = 2.0 * p.radius;
    -h / (r2 + (r2 * r2 + h).max(0.0).sqrt())
}
