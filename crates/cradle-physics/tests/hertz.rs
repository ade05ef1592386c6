//! Hertz contact: energy and momentum through a contact, the velocity split of a
//! struck chain and its independence of stiffness and impact speed, and frame-rate
//! independence of the engine in Hertz mode.

mod common;

use cradle_physics::hertz::{run_phase, stiffness};
use cradle_physics::{Cradle, CradleParams, Integrator};

/// Steel balls of 2 cm radius on 16 cm strings, as the default asset.
fn steel(balls: usize, gravity: f64) -> CradleParams {
    steel_on(balls, gravity, 0.16)
}

/// Steel balls of 2 cm radius on strings `length` (m) long.
fn steel_on(balls: usize, gravity: f64, length: f64) -> CradleParams {
    CradleParams {
        gravity,
        length,
        ..common::steel(balls)
    }
}

/// The balls' angular velocities, as fractions of the striker's, after ball 0
/// strikes the resting touching chain at `speed` (m/s) and every pair has come apart.
fn split(p: &CradleParams, k: f64, speed: f64) -> Vec<f64> {
    let n = p.balls;
    let theta = vec![0.0; n];
    let mut omega = vec![0.0; n];
    omega[0] = speed / p.length;
    let end = run_phase(p, k, 0.0, &theta, &omega, f64::INFINITY);
    assert!(end.separated, "the chain comes apart");
    end.omega.iter().map(|w| w / omega[0]).collect()
}

#[test]
fn stiffness_follows_the_hertz_formula() {
    // E* = E / (2 (1 - nu^2)) = 1.5e11 / 1.5 for nu = 0.5; R* = r/2 = 0.5 m:
    // k = 4/3 * E* * sqrt(0.5), written out by hand.
    let k = stiffness(1.5e11, 0.5, 1.0);
    let want = 4.0 / 3.0 * 1.0e11 * 0.5_f64.sqrt();
    assert!((k - want).abs() <= 1e-15 * want, "{k} vs {want}");
}

#[test]
fn a_two_ball_contact_conserves_energy_and_momentum() {
    // Gravity a billionth of Earth's and 1 km strings: the pivots' reactions, the
    // only outside forces, then move the pair's momentum by ~1e-15 of itself over
    // the 0.1 ms contact, so what is left is the integrator's error.
    let p = steel_on(2, 9.81e-9, 1000.0);
    let k = p.hertz.unwrap();
    let (theta, omega) = (vec![0.0, 0.0], vec![0.5 / p.length, 0.0]);
    let e0 = p.energy(&theta, &omega);
    let end = run_phase(&p, k, 0.0, &theta, &omega, f64::INFINITY);
    assert!(end.separated);
    let e1 = p.energy(&end.theta, &end.omega);
    let rel = (e1 - e0).abs() / e0;
    assert!(rel < 1e-9, "energy error {rel:e}");
    // Horizontal momentum of the centres, m L sum(cos(theta) omega).
    let momentum = |th: &[f64], w: &[f64]| {
        th.iter()
            .zip(w)
            .map(|(t, w)| p.mass * p.length * t.cos() * w)
            .sum::<f64>()
    };
    let m0 = momentum(&theta, &omega);
    let dm = (momentum(&end.theta, &end.omega) - m0).abs() / m0;
    assert!(dm < 1e-9, "momentum error {dm:e}");
    // Two equal elastic balls exchange velocities.
    assert!(end.omega[0].abs() < 1e-6 * omega[0], "{:?}", end.omega);
    assert!(
        (end.omega[1] / omega[0] - 1.0).abs() < 1e-6,
        "{:?}",
        end.omega
    );
    // The contact lasts about 2.94 (m*^2 / (k^2 v))^(1/5), Hertz's formula: about
    // 0.1 ms here; allow the wide band that the separation test allows.
    let m_star = p.mass / 2.0;
    let tau = 2.943 * (m_star * m_star / (k * k * 0.5)).powf(0.2);
    assert!(end.t > 0.8 * tau && end.t < 1.3 * tau, "{} vs {tau}", end.t);
}

#[test]
fn energy_is_conserved_through_every_contact_of_a_swing() {
    // The default cradle in Hertz mode for 3 s (10 strikes each way): the exact
    // flights keep energy to round-off, so the drift is the contacts' alone.
    let p = steel(5, 9.81);
    let mut c = Cradle::new(p, Integrator::Exact, 1e-3, 1, 30f64.to_radians());
    let mut worst: f64 = 0.0;
    for i in 1..=300 {
        let s = c.snapshot(f64::from(i) * 0.01);
        worst = worst.max(c.energy_rel_error(&s).abs());
        assert!(s.theta.iter().chain(&s.omega).all(|x| x.is_finite()));
    }
    let s = c.snapshot(3.0);
    assert!(s.collisions >= 20, "{} contacts", s.collisions);
    assert!(worst < 1e-9, "energy drift {worst:e}");
}

#[test]
fn the_split_does_not_depend_on_stiffness_or_speed() {
    // Hertz's law has no length or time scale of its own: changing k or v only
    // rescales the contact's time and depth, so the fractions agree to the
    // tolerance the integrator keeps (1e-13 per step; 1e-7 leaves room for
    // thousands of steps). Strings 1 km long and almost no gravity take out the
    // pendulum's own scales: the contact's depth against the length (1e-8 at the
    // softest here) and gravity's impulse over the contact.
    for n in [3, 5, 10] {
        let p = steel_on(n, 9.81e-9, 1000.0);
        let k0 = p.hertz.unwrap();
        let reference = split(&p, k0, 0.5);
        for (k, v) in [
            (k0 * 1e-3, 0.5),
            (k0 * 1e3, 0.5),
            (k0, 0.005),
            (k0, 5.0),
            (k0 * 30.0, 0.05),
        ] {
            let other = split(&p, k, v);
            for (a, b) in reference.iter().zip(&other) {
                assert!(
                    (a - b).abs() < 1e-7,
                    "n={n} k={k:e} v={v}: {reference:?} vs {other:?}"
                );
            }
        }
        // What real cradles do: the striker recoils slightly, the second-to-last
        // ball moves forward slightly, and the last leaves with nearly everything.
        assert!(reference[0] < 0.0 && reference[0] > -0.2, "{reference:?}");
        assert!(
            reference[n - 2] > 0.0 && reference[n - 2] < 0.2,
            "{reference:?}"
        );
        assert!(
            reference[n - 1] > 0.8 && reference[n - 1] < 1.0,
            "{reference:?}"
        );
        // Momentum of the whole chain (equal inertia: the sum of fractions) is 1.
        let total: f64 = reference.iter().sum();
        assert!((total - 1.0).abs() < 1e-9, "momentum {total}");
        println!("n={n} split {reference:?}");
    }
}

#[test]
fn the_split_holds_with_real_gravity_in_the_engine() {
    // In the engine, with Earth's gravity, the striker comes in from 20 deg; the
    // split read just after the contact agrees with the gravity-free one to 1e-3:
    // gravity acts for the ~0.5 ms of the phase at angles below 1e-3 rad.
    let p = steel(5, 9.81);
    let free = split(&steel_on(5, 9.81e-9, 1000.0), p.hertz.unwrap(), 0.5);
    let speed = p.release_speed(20f64.to_radians());
    let (theta, mut omega) = (vec![0.0; 5], vec![0.0; 5]);
    omega[0] = speed / p.length;
    let mut c = Cradle::from_state(p, Integrator::Exact, 1e-3, &theta, &omega);
    let s = c.snapshot(2e-3);
    for (a, b) in free.iter().zip(&s.omega) {
        assert!((a - b / omega[0]).abs() < 1e-3, "{free:?} vs {:?}", s.omega);
    }
}

#[test]
fn hertz_states_do_not_depend_on_the_frame_rate() {
    let p = steel(5, 9.81);
    let run = |fps: f64| {
        let mut c = Cradle::new(p, Integrator::Exact, 1e-3, 2, 25f64.to_radians());
        let frames = (2.0 * fps) as usize;
        for i in 0..frames {
            c.snapshot(i as f64 / fps);
        }
        c.snapshot(2.0)
    };
    let (a, b) = (run(30.0), run(144.0));
    for (x, y) in a.theta.iter().zip(&b.theta) {
        assert!((x - y).abs() < 1e-12, "{:?} vs {:?}", a.theta, b.theta);
    }
    assert_eq!(a.collisions, b.collisions);
}

#[test]
fn fixed_step_integrators_run_hertz_contacts_too() {
    // rk4 at 1e-4 s between contacts, the Hertz phases adaptive inside: after 1 s
    // (three strikes) it agrees with the exact engine to the integrator's error.
    let p = steel(3, 9.81);
    let mut exact = Cradle::new(p, Integrator::Exact, 1e-4, 1, 20f64.to_radians());
    let mut rk4 = Cradle::new(p, Integrator::Rk4, 1e-4, 1, 20f64.to_radians());
    let (a, b) = (exact.snapshot(1.0), rk4.snapshot(1.0));
    assert!(b.collisions >= 3, "{} contacts", b.collisions);
    for (x, y) in a.theta.iter().zip(&b.theta) {
        assert!((x - y).abs() < 1e-6, "{:?} vs {:?}", a.theta, b.theta);
    }
    assert!(rk4.energy_rel_error(&b).abs() < 1e-9);
}

/// Steel balls of 0.1 mm on 16 cm strings, stiff (E = 1e13 Pa), with the
/// viscoelastic constant `dissipation` (s).
fn tiny_stiff(balls: usize, dissipation: f64) -> CradleParams {
    let r = 1e-4;
    CradleParams {
        radius: r,
        mass: 7850.0 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3),
        hertz: Some(stiffness(1e13, 0.29, r)),
        dissipation,
        ..common::steel(balls)
    }
}

#[test]
fn a_phase_advances_even_where_no_step_meets_the_error_bound() {
    // Balls of 0.1 mm, stiff (E = 1e13 Pa) and damped far beyond the model's
    // range (A = 1e-3 s, ten million contact times; the config refuses it):
    // the error bound is not met by any step f64 can take, and the phase once
    // ended where it began, not apart, to be started again from there for
    // ever. Now it takes its shortest steps regardless, and advances.
    let p = tiny_stiff(5, 1e-3);
    let k = p.hertz.expect("hertz");
    let t0 = 0.215_287_483_507_384_3;
    let mut omega = vec![0.0; 5];
    omega[0] = p.w0();
    let end = run_phase(&p, k, t0, &[0.0; 5], &omega, f64::INFINITY);
    assert!(end.t > t0, "the phase advanced: {} after {t0}", end.t);
    assert!(end.theta.iter().chain(&end.omega).all(|x| x.is_finite()));
}

#[test]
fn a_contact_of_tiny_balls_late_in_a_run_advances_and_comes_apart() {
    // A contact of tiny stiff balls (0.1 mm, E = 1e13 Pa) late in a run, where
    // f64 resolves time only to 1.8e-15 s and the contact lasts ~1e-9 s.
    let p = tiny_stiff(2, 0.0);
    let k = p.hertz.expect("hertz");
    // Touching at 0.5 rad, ball 0 closing at 1 rad/s.
    let end = run_phase(&p, k, 13.028, &[0.5, 0.5], &[1.0, 0.0], f64::INFINITY);
    assert!(end.separated, "the pair comes apart");
    assert!(end.t > 13.028, "the phase advanced: {}", end.t);
    // Equal elastic balls swap their speeds; over the contact gravity changes
    // them by far less than 1e-6 rad/s: 1e-5 is a safe bound.
    assert!(end.omega[0].abs() < 1e-5, "{:?}", end.omega);
    assert!((end.omega[1] - 1.0).abs() < 1e-5, "{:?}", end.omega);
}
