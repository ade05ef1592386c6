//! Behaviour of the cradle's physics: energy, k in -> k out, frame-rate
//! independence, determinism, restitution, and agreement with the closed form.

use cradle_physics::elliptic::{ellip_k, sncndn};
use cradle_physics::{Cradle, CradleParams, Integrator};

fn params(balls: usize, gap: f64, restitution: f64) -> CradleParams {
    CradleParams {
        balls,
        radius: 0.02,
        mass: 0.263,
        length: 0.16,
        gap,
        gravity: 9.81,
        restitution,
        hertz: None,
        dissipation: 0.0,
        drag: 0.0,
    }
}

fn exact(balls: usize, lift: usize, angle_deg: f64) -> Cradle {
    Cradle::new(
        params(balls, 0.0, 1.0),
        Integrator::Exact,
        1e-3,
        lift,
        angle_deg.to_radians(),
    )
}

/// The angle of the one swinging ball of an ideal cradle with one ball lifted, from
/// the closed form alone: the pendulum released from -A swings through; while it is
/// left of the vertical, ball 0 carries it; right of it, the last ball.
fn single_swing(p: &CradleParams, amplitude: f64, t: f64) -> f64 {
    let k = (0.5 * amplitude).sin();
    let m = k * k;
    // Released at rest from -A: u = w0 t - K.
    let (sn, _, _) = sncndn(p.w0() * t - ellip_k(m), m);
    2.0 * (k * sn).clamp(-1.0, 1.0).asin()
}

#[test]
fn one_lifted_ball_follows_the_closed_form_at_179_degrees() {
    let p = params(5, 0.0, 1.0);
    let amplitude = 179f64.to_radians();
    let mut c = Cradle::new(p, Integrator::Exact, 1e-3, 1, amplitude);
    let mut worst = 0.0_f64;
    for n in 0..=3000 {
        let t = f64::from(n) * 0.01;
        let s = c.snapshot(t);
        let phi = single_swing(&p, amplitude, t);
        let want_left = phi.min(0.0);
        let want_right = phi.max(0.0);
        worst = worst
            .max((s.theta[0] - want_left).abs())
            .max((s.theta[4] - want_right).abs());
        assert!(
            s.theta[1..4]
                .iter()
                .chain(&s.omega[1..4])
                .all(|v| *v == 0.0),
            "t = {t}: middle balls moved"
        );
    }
    // Impacts are located to 1e-14 s and balls move at < 30 rad/s near 179 degrees:
    // each impact shifts the phase by < 1e-12 rad, and 30 s holds ~40 impacts.
    assert!(worst < 1e-10, "max angle error {worst:e} rad");
}

#[test]
fn energy_is_conserved_over_ten_thousand_seconds() {
    let mut c = exact(5, 2, 45.0);
    let e0 = c.initial_energy();
    let mut worst = 0.0_f64;
    for n in 0..=1000 {
        let s = c.snapshot(f64::from(n) * 10.0);
        worst = worst.max(((c.energy(&s) - e0) / e0).abs());
    }
    // Each impact swaps angular velocities exactly and each flight conserves its
    // own energy to round-off: the drift is a random walk of ~1e-16 steps.
    assert!(worst < 1e-12, "relative energy drift {worst:e}");
}

#[test]
fn k_lifted_balls_in_exactly_k_out_for_every_k_below_n_up_to_12() {
    for n in 2..=12 {
        for k in 1..n {
            let mut c = exact(n, k, 40.0);
            let e_ball = c.params().ball_energy(-40f64.to_radians(), 0.0);
            let mut t = 0.0;
            // 100 strikes: each strike is k (n - k) pairwise impacts.
            while c.snapshot(t).collisions < 100 * (k * (n - k)) as u64 {
                let s = c.snapshot(t);
                let moving: Vec<usize> = (0..n)
                    .filter(|&i| s.theta[i] != 0.0 || s.omega[i] != 0.0)
                    .collect();
                let left: Vec<usize> = (0..k).collect();
                let right: Vec<usize> = (n - k..n).collect();
                // At an instant when the block is exactly at the bottom, nothing
                // reads as moving; otherwise k balls at one end, the rest at rest.
                assert!(
                    moving.is_empty() || moving == left || moving == right,
                    "n={n} k={k} t={t}: moving {moving:?}"
                );
                for &i in &moving {
                    assert_eq!(
                        (s.theta[i], s.omega[i]),
                        (s.theta[moving[0]], s.omega[moving[0]]),
                        "outgoing balls move alike"
                    );
                    let e = c.params().ball_energy(s.theta[i], s.omega[i]);
                    // Amplitude unchanged: each moving ball keeps the lifted energy.
                    assert!(
                        (e - e_ball).abs() < 1e-12 * e_ball,
                        "n={n} k={k} t={t}: ball energy {e} vs {e_ball}"
                    );
                }
                t += 0.013;
            }
        }
    }
}

fn state_after(integrator: Integrator, hz: f64) -> Vec<f64> {
    let mut c = Cradle::new(
        params(5, 0.001, 1.0),
        integrator,
        1e-3,
        2,
        50f64.to_radians(),
    );
    let frames = (10.0 * hz) as u32;
    let mut last = Vec::new();
    for n in 0..=frames {
        last = c.snapshot(f64::from(n) / hz).theta;
    }
    last
}

#[test]
fn state_at_ten_seconds_does_not_depend_on_the_frame_rate() {
    for integrator in [Integrator::Exact, Integrator::Rk4, Integrator::Verlet] {
        let a = state_after(integrator, 30.0);
        let b = state_after(integrator, 144.0);
        for (x, y) in a.iter().zip(&b) {
            // The promise: 1e-12 rad. Events are found on windows anchored at the
            // last event, never at the sample times, so in fact they agree exactly.
            assert!((x - y).abs() <= 1e-12, "{integrator:?}: {x} vs {y}");
        }
    }
}

#[test]
fn runs_are_deterministic() {
    let run = || {
        let mut c = Cradle::new(
            params(7, 0.0005, 0.9),
            Integrator::Exact,
            1e-3,
            3,
            70f64.to_radians(),
        );
        (0..500)
            .map(|n| c.snapshot(f64::from(n) * 0.02))
            .collect::<Vec<_>>()
    };
    assert_eq!(run(), run());
}

#[test]
fn two_balls_keep_one_plus_e_squared_over_two_of_the_energy() {
    for e in [0.0, 0.25, 0.5, 0.8, 1.0] {
        let mut c = Cradle::new(
            params(2, 0.0, e),
            Integrator::Exact,
            1e-3,
            1,
            30f64.to_radians(),
        );
        let e0 = c.initial_energy();
        // The first impact happens at a quarter period (~0.2 s); sample just after.
        let mut t = 0.0;
        while c.snapshot(t).collisions == 0 {
            t += 0.001;
        }
        let s = c.snapshot(t);
        let ratio = c.energy(&s) / e0;
        let want = 0.5 * (1.0 + e * e);
        // Flight conserves energy to round-off; the impulse formula is exact.
        assert!(
            (ratio - want).abs() < 1e-12,
            "e = {e}: ratio {ratio}, want {want}"
        );
    }
}

#[test]
fn touching_balls_with_restitution_below_one_end_as_one_block_in_finitely_many_impacts() {
    for lift in [1, 2, 4] {
        let mut c = Cradle::new(
            params(5, 0.0, 0.6),
            Integrator::Exact,
            1e-3,
            lift,
            40f64.to_radians(),
        );
        let at_100 = c.snapshot(100.0);
        let at_300 = c.snapshot(300.0);
        assert!(at_100.collisions > 0);
        assert_eq!(
            at_100.collisions, at_300.collisions,
            "lift {lift}: impacts went on after 100 s"
        );
        // One block: every ball in exactly the same state.
        assert!(
            at_300.theta.iter().all(|t| *t == at_300.theta[0]),
            "{:?}",
            at_300.theta
        );
        assert!(
            at_300.omega.iter().all(|w| *w == at_300.omega[0]),
            "{:?}",
            at_300.omega
        );
        let kept = c.energy(&at_300) / c.initial_energy();
        assert!(kept > 0.0 && kept < 1.0, "kept {kept}");
    }
}

#[test]
fn balls_with_gaps_and_restitution_below_one_never_storm() {
    let mut c = Cradle::new(
        params(5, 0.001, 0.6),
        Integrator::Exact,
        1e-3,
        1,
        40f64.to_radians(),
    );
    let (mut last_e, mut last_n) = (c.initial_energy(), 0);
    for second in 1..=300 {
        let s = c.snapshot(f64::from(second));
        let e = c.energy(&s);
        // Energy only leaves; round-off of one flight is ~1e-16 relative.
        assert!(
            e <= last_e * (1.0 + 1e-12),
            "t = {second}: energy grew {last_e} -> {e}"
        );
        // A pair meets at most a few times per swing (~0.8 s): a Zeno storm would
        // show as thousands of impacts in a second.
        assert!(
            s.collisions - last_n < 100,
            "t = {second}: {} impacts in a second",
            s.collisions - last_n
        );
        (last_e, last_n) = (e, s.collisions);
    }
}

#[test]
fn integrators_converge_to_the_exact_flight_at_their_order() {
    // One ball alone: no impacts, pure flight, against the closed form at t = 2 s.
    let p = params(1, 0.0, 1.0);
    let amplitude = 60f64.to_radians();
    let exact_theta = single_swing(&p, amplitude, 2.0);
    for (integrator, order) in [
        (Integrator::Euler, 1.0),
        (Integrator::Verlet, 2.0),
        (Integrator::Rk4, 4.0),
        (Integrator::Yoshida4, 4.0),
    ] {
        let err = |dt: f64| {
            let mut c = Cradle::new(p, integrator, dt, 1, amplitude);
            (c.snapshot(2.0).theta[0] - exact_theta).abs()
        };
        let (coarse, fine) = (err(4e-3), err(2e-3));
        let observed = (coarse / fine).log2();
        // Halving dt divides the error by 2^order; 0.35 of slack covers the
        // pre-asymptotic terms at these steps.
        assert!(
            (observed - order).abs() < 0.35,
            "{integrator:?}: observed order {observed}"
        );
    }
}

#[test]
fn integrators_pass_a_strike_through_the_chain() {
    for integrator in [Integrator::Verlet, Integrator::Rk4, Integrator::Yoshida4] {
        let mut c = Cradle::new(params(5, 0.0, 1.0), integrator, 1e-4, 1, 30f64.to_radians());
        let s = c.snapshot(0.4);
        assert!(
            s.collisions >= 4,
            "{integrator:?}: {} impacts",
            s.collisions
        );
        assert!(
            s.theta[1..4].iter().all(|t| *t == 0.0),
            "{integrator:?}: middle moved {:?}",
            s.theta
        );
        assert!(
            s.theta[4] > 0.0 && s.theta[0] == 0.0,
            "{integrator:?}: {:?}",
            s.theta
        );
    }
}

#[test]
fn a_snapshot_by_a_deadline_is_the_exact_state_at_the_time_it_reached() {
    // Every engine: ideal and Hertz contacts (exact), drag (damped), RK4
    // (stepped). With the deadline already past nothing is computed and the
    // state is the start's; with time to spare it is the state at the time
    // asked, bit for bit what a call without a deadline gives.
    let mut hertz = params(5, 0.0, 1.0);
    hertz.hertz = Some(cradle_physics::hertz::stiffness(2.0e11, 0.29, hertz.radius));
    let mut damped = hertz;
    damped.dissipation = 5e-7;
    damped.drag = CradleParams::drag_of(1.2, 0.47, damped.radius);
    let cases = [
        (params(5, 0.0, 1.0), Integrator::Exact),
        (hertz, Integrator::Exact),
        (damped, Integrator::Exact),
        (params(5, 0.0, 1.0), Integrator::Rk4),
    ];
    let past = std::time::Instant::now();
    for (p, method) in cases {
        let new = || Cradle::new(p, method, 1e-3, 1, 30f64.to_radians());
        let (mut a, mut b) = (new(), new());
        let start = a.snapshot_by(2.0, past);
        assert_eq!(start.t, 0.0, "{method:?}: nothing done past the deadline");
        assert_eq!(start.theta, b.snapshot(0.0).theta);
        let later = std::time::Instant::now() + std::time::Duration::from_mins(10);
        let s = a.snapshot_by(2.0, later);
        assert_eq!(s.t, 2.0, "{method:?}");
        assert_eq!(s, b.snapshot(2.0), "{method:?}: the same state");
    }
}
