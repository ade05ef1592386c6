//! The stress suite's scenarios: extreme cradles, each with the limits it must
//! keep (`Scenario`), run by [`super::run`].

use super::Scenario;
use crate::config::Config;
use crate::physics::{CradleParams, hertz};

/// The default asset's cradle (5 steel balls of 2 cm on 16 cm strings, ideal,
/// e = 1) with `balls` balls.
fn base(balls: usize) -> CradleParams {
    CradleParams {
        balls,
        ..Config::default().cradle_params()
    }
}

/// The suite, with every duration multiplied by `scale`.
#[must_use]
#[expect(
    clippy::too_many_lines,
    reason = "one entry per scenario: a list, not logic"
)]
pub fn scenarios(scale: f64) -> Vec<Scenario> {
    let case =
        |name: &str, params: CradleParams, lift: usize, angle_deg: f64, duration: f64| Scenario {
            name: name.to_owned(),
            params,
            lift,
            angle_deg,
            duration: duration * scale,
            sample_every: 0.01,
            energy_tol: 1e-10,
            overlap_tol: Some(1e-12),
            first_strike_energy: None,
            rest_by: None,
        };
    let inelastic = |e: f64, balls: usize, gap: f64| CradleParams {
        restitution: e,
        gap,
        ..base(balls)
    };
    let mut out = vec![
        // 20 balls into 180: 3600 impacts per strike, ~2.4 strikes a second:
        // 1e6 impacts in 116 s.
        Scenario {
            sample_every: 0.05,
            ..case(
                "200 balls, 20 lifted (3600 per strike)",
                base(200),
                20,
                30.0,
                120.0,
            )
        },
        case("179.9 deg, N = 1", base(1), 1, 179.9, 20.0),
        case("179.9 deg, N = 2, k = 1", base(2), 1, 179.9, 20.0),
        case("179.9 deg, N = 200, k = 199", base(200), 199, 179.9, 5.0),
        case(
            "gaps of 1 mm: two-ball impacts",
            CradleParams {
                gap: 1e-3,
                ..base(5)
            },
            2,
            40.0,
            60.0,
        ),
        Scenario {
            first_strike_energy: Some(0.2),
            rest_by: Some(10.0),
            ..case("e = 0, 5 touching", inelastic(0.0, 5, 0.0), 1, 30.0, 20.0)
        },
        Scenario {
            first_strike_energy: Some(0.625),
            rest_by: Some(20.0),
            ..case("e = 0.5, 2 touching", inelastic(0.5, 2, 0.0), 1, 30.0, 40.0)
        },
        // Apart balls swing at their own amplitudes, so their periods differ and
        // they meet again: energy only decays here, with no rest to reach.
        case(
            "e = 0.5, 5 with gaps",
            inelastic(0.5, 5, 2e-3),
            2,
            30.0,
            60.0,
        ),
        case(
            "tiny: r 0.2 mm, L 1 mm, g 1e-3",
            CradleParams {
                radius: 2e-4,
                length: 1e-3,
                mass: 1e-8,
                gravity: 1e-3,
                ..base(5)
            },
            2,
            60.0,
            200.0,
        ),
        case(
            "huge: L 1 km, g 1e3",
            CradleParams {
                radius: 10.0,
                length: 1000.0,
                mass: 3e7,
                gravity: 1e3,
                ..base(5)
            },
            1,
            60.0,
            60.0,
        ),
        case(
            "strong gravity: g 1e4",
            CradleParams {
                gravity: 1e4,
                ..base(5)
            },
            1,
            120.0,
            2.0,
        ),
    ];
    let steel = base(5);
    out.push(Scenario {
        // Each contact keeps energy to ~1e-12 (tests/hertz.rs); a few hundred
        // contacts stay within 1e-9.
        energy_tol: 1e-9,
        overlap_tol: None,
        ..case(
            "hertz: 5 steel balls",
            CradleParams {
                hertz: Some(hertz::stiffness(2e11, 0.29, steel.radius)),
                dissipation: 0.0,
                drag: 0.0,
                ..steel
            },
            1,
            30.0,
            10.0,
        )
    });
    // The realistic asset's losses: viscoelastic contacts and air drag, with the
    // damped engine integrating everything. Energy may only fall (to 1e-9 of
    // the start, the integrator's error over the run); no pair presses deeper
    // than a Hertz contact at the fastest speed of the swing, which dissipation
    // only makes shallower: (5 m_eff v^2 / (4 k))^(2/5), m_eff = I / (2 L^2).
    let k = hertz::stiffness(2e11, 0.29, steel.radius);
    let lossy = CradleParams {
        hertz: Some(k),
        dissipation: 5e-7,
        drag: CradleParams::drag_of(1.2, 0.47, steel.radius),
        ..steel
    };
    let v = lossy.release_speed(30f64.to_radians());
    let m_eff = lossy.inertia() / (2.0 * lossy.length * lossy.length);
    out.push(Scenario {
        energy_tol: 1e-9,
        overlap_tol: Some((5.0 * m_eff * v * v / (4.0 * k)).powf(0.4)),
        ..case("viscoelastic and drag: 5 steel balls", lossy, 1, 30.0, 10.0)
    });
    out
}
