//! Dissipative contacts and air drag: the restitution of the viscoelastic law
//! against its asymptotic theory, a force that never pulls, energy that never
//! grows and is all accounted for, and the damped engine's independence of the
//! frame rate.

mod common;

use cradle_physics::hertz::run_phase;
use cradle_physics::{Cradle, CradleParams, Integrator};
use proptest::prelude::*;

/// Steel balls of 2 cm radius on 16 cm strings, Hertz contact with dissipative
/// constant `a` (s) and drag constant `drag` (kg/m).
fn steel(balls: usize, a: f64, drag: f64) -> CradleParams {
    CradleParams {
        dissipation: a,
        drag,
        ..common::steel(balls)
    }
}

/// Drag of a 2 cm ball in air at 20 C (1.2 kg/m^3, drag coefficient 0.47).
const AIR: f64 = 0.5 * 1.2 * 0.47 * std::f64::consts::PI * 0.02 * 0.02;

/// Restitution of ball 0 striking ball 1 at rest at `speed` (m/s) at the bottom.
fn restitution(p: &CradleParams, speed: f64) -> f64 {
    let w = speed / p.length;
    let end = run_phase(
        p,
        p.hertz.unwrap(),
        0.0,
        &[0.0; 2],
        &[w, 0.0],
        f64::INFINITY,
    );
    assert!(end.separated);
    (end.omega[1] - end.omega[0]) / w
}

/// First order in `A` of `1 - e` for viscoelastic Hertz spheres (Schwager and
/// Poschel 1998; Ramirez et al. 1999), derived here from the energy the
/// dissipative force takes along the elastic collision:
/// `1 - e = 3 (5/4)^(3/5) (2/5) B(3/5, 3/2) A (k / m_eff)^(2/5) v^(1/5)`, and
/// `(2/5) B(3/5, 3/2) = 0.504 46...`, so the constant is 1.730 2 (the literature's
/// `C1 (3/2)` with `C1 = 1.153 44`). `m_eff` of two pendulums meeting at the
/// bottom is `I / (2 L^2)`, the inertia each presents at its centre.
fn first_order(p: &CradleParams, speed: f64) -> f64 {
    let m_eff = p.inertia() / (2.0 * p.length * p.length);
    1.153_44 * 1.5 * p.dissipation * (p.hertz.unwrap() / m_eff).powf(0.4) * speed.powf(0.2)
}

#[test]
fn restitution_follows_the_viscoelastic_theory() {
    // A small constant, so 1 - e is about 1e-3: the next order of the series is
    // about (1 - e) times the first (C2 / C1^2 = 0.6), so the first order alone
    // must agree to about 0.03%; the tolerance is 0.1%.
    let p = steel(2, 1e-8, 0.0);
    for v in [0.1, 0.5, 1.0] {
        let loss = 1.0 - restitution(&p, v);
        let want = first_order(&p, v);
        assert!(
            (loss / want - 1.0).abs() < 1e-3,
            "at {v} m/s: 1 - e = {loss:e}, theory {want:e}"
        );
    }
}

#[test]
fn restitution_falls_with_impact_speed_as_v_to_the_fifth() {
    // The realistic asset's constant: e falls with speed, and 1 - e grows as
    // v^(1/5) (to the same 1% the next order allows at 1 - e ~ 0.02).
    let p = steel(2, 5e-7, 0.0);
    let e: Vec<f64> = [0.1, 0.5, 1.0]
        .iter()
        .map(|&v| restitution(&p, v))
        .collect();
    assert!(e[0] > e[1] && e[1] > e[2], "{e:?}");
    assert!(e.iter().all(|&x| (0.95..1.0).contains(&x)), "{e:?}");
    let ratio = (1.0 - e[2]) / (1.0 - e[0]);
    let want = 10f64.powf(0.2);
    assert!((ratio / want - 1.0).abs() < 0.02, "{ratio} vs {want}");
}

#[test]
fn zero_dissipation_is_elastic_hertz_bit_for_bit() {
    let elastic = steel(3, 0.0, 0.0);
    let end = run_phase(
        &elastic,
        elastic.hertz.unwrap(),
        0.0,
        &[0.0; 3],
        &[3.0, 0.0, 0.0],
        f64::INFINITY,
    );
    assert_eq!(end.lost, [0.0; 2]);
    let mut c = Cradle::new(elastic, Integrator::Exact, 1e-3, 1, 0.5);
    let s = c.snapshot(3.0);
    assert_eq!(s.lost, [0.0; 2]);
    // The energy error stays the elastic engine's: no balance term added.
    assert!(c.energy_rel_error(&s).abs() < 1e-9);
}

#[test]
fn a_heavily_damped_contact_never_pulls() {
    // A = 1e-4 s makes the contact overdamped: unclamped, the dissipative force
    // would pull the balls together as they separate, slowing the struck ball.
    // Clamped at zero, the struck ball only ever speeds up, and the striker only
    // ever slows down. Checked at 400 cuts of the contact.
    let p = steel(2, 1e-4, 0.0);
    let (k, w) = (p.hertz.unwrap(), 0.5 / p.length);
    let whole = run_phase(&p, k, 0.0, &[0.0; 2], &[w, 0.0], f64::INFINITY);
    assert!(whole.separated);
    let mut last = (w, 0.0);
    for i in 1..=400 {
        let t = whole.t * f64::from(i) / 400.0;
        let cut = run_phase(&p, k, 0.0, &[0.0; 2], &[w, 0.0], t);
        // Gravity changes the speeds by g t / L ~ 1e-3 rad/s over the contact's
        // 0.1 ms; the tolerance allows it.
        assert!(
            cut.omega[1] >= last.1 - 1e-3,
            "struck ball pulled back at {t}"
        );
        assert!(
            cut.omega[0] <= last.0 + 1e-3,
            "striker pulled forward at {t}"
        );
        last = (cut.omega[0], cut.omega[1]);
    }
    assert!(whole.lost[0] > 0.0);
}

#[test]
fn the_damped_engine_does_not_depend_on_the_frame_rate() {
    // Its steps are taken from the start, never at sample times, and a state
    // between step points is one step from the point before: the same bits at
    // any frame rate.
    let p = steel(5, 5e-7, AIR);
    let run = |fps: f64| {
        let mut c = Cradle::new(p, Integrator::Exact, 1e-3, 1, 30f64.to_radians());
        for i in 0..(3.0 * fps) as usize {
            c.snapshot(i as f64 / fps);
        }
        c.snapshot(3.0)
    };
    let (a, b) = (run(30.0), run(144.0));
    assert_eq!(a, b);
    assert!(a.collisions > 0 && a.lost[0] > 0.0 && a.lost[1] > 0.0);
}

#[test]
fn drag_alone_matches_the_energy_it_takes() {
    // No contacts (one ball), only drag: the energy lost is booked as drag,
    // the balance holds to the integrator's tolerance (1e-9 of the energy), and
    // 10 s in air at 20 C take a small share (0.1% to 10%) of a 30 degree swing.
    let p = steel(1, 0.0, AIR);
    let mut c = Cradle::new(p, Integrator::Exact, 1e-3, 1, 30f64.to_radians());
    let s = c.snapshot(10.0);
    let e0 = c.initial_energy();
    assert_eq!(s.lost[0], 0.0);
    assert!(
        (1e-3..0.1).contains(&(s.lost[1] / e0)),
        "{}",
        s.lost[1] / e0
    );
    assert!(
        c.energy_rel_error(&s).abs() < 1e-9,
        "{}",
        c.energy_rel_error(&s)
    );
}

#[test]
fn touching_lifted_balls_under_drag_keep_the_energy_balance() {
    // Found by the property test: two lifted balls touching each other press and
    // part again and again; stepping across each contact's onset left 2e-8 of
    // the energy unbooked. Steps now stop at an onset: the balance holds to
    // 1e-9 (measured 4e-11).
    let p = steel(6, 0.0, 0.0012);
    let mut c = Cradle::new(p, Integrator::Exact, 1e-3, 2, 13.527_f64.to_radians());
    for i in 1..=300 {
        let s = c.snapshot(f64::from(i) * 0.01);
        let balance = c.energy_rel_error(&s);
        assert!(balance.abs() < 1e-9, "{balance:e} at {} s", s.t);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn energy_never_grows_with_dissipation(
        balls in 2usize..=6,
        lift in 1usize..=3,
        angle in 5.0f64..60.0,
        a in prop_oneof![Just(0.0), 1e-8f64..1e-5],
        drag in prop_oneof![Just(0.0), 1e-5f64..1e-2],
        gap in prop_oneof![Just(0.0), 0.0f64..0.002],
    ) {
        prop_assume!(a > 0.0 || drag > 0.0);
        let p = CradleParams { gap, ..steel(balls, a, drag) };
        let mut c = Cradle::new(p, Integrator::Exact, 1e-3, lift.min(balls), angle.to_radians());
        let e0 = c.initial_energy();
        let mut last = e0;
        for i in 1..=300 {
            let s = c.snapshot(f64::from(i) * 0.01);
            let e = c.energy(&s);
            prop_assert!(e.is_finite() && s.theta.iter().all(|x| x.is_finite()));
            // Never more than the last sample's, beyond the integrator's
            // tolerance (each step's error is ~1e-13 of the energy in play).
            prop_assert!(e <= last + 1e-10 * e0, "grew {} at {}", (e - last) / e0, s.t);
            // And what left is booked: the balance holds to 1e-8.
            prop_assert!(c.energy_rel_error(&s).abs() < 1e-8, "{}", c.energy_rel_error(&s));
            last = e;
        }
    }
}
