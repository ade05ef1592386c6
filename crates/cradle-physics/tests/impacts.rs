//! The impacts the engines report: when, which pair, how fast, where, and for
//! Hertz contact how long, how hard and the impulse passed; their courses
//! (force curves, velocities before and after); the same at any frame rate.

mod common;

use cradle_physics::hertz::contact_time;
use cradle_physics::{Course, Cradle, CradleParams, Impact, Integrator};

/// The default cradle of `balls` balls; ideal impacts unless `hertz`.
fn steel(balls: usize, hertz: bool) -> CradleParams {
    let p = common::steel(balls);
    CradleParams {
        hertz: p.hertz.filter(|_| hertz),
        ..p
    }
}

/// Every impact of `cradle` up to `until` (s), its snapshots `frame` (s) apart.
fn impacts(cradle: &mut Cradle, frame: f64, until: f64) -> Vec<Impact> {
    cradle.record_impacts();
    let mut all = Vec::new();
    let mut n = 1.0;
    while n * frame <= until {
        let s = cradle.snapshot(n * frame);
        all.extend(cradle.take_impacts(s.t));
        n += 1.0;
    }
    all
}

/// The complete elliptic integral K(k) by the arithmetic-geometric mean,
/// written here apart from the engine's own elliptic functions.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, (1.0 - k * k).sqrt());
    for _ in 0..40 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

#[test]
fn an_ideal_striker_passes_through_the_chain_at_a_quarter_period_at_its_release_speed() {
    let p = steel(5, false);
    let angle = 30f64.to_radians();
    let mut cradle = Cradle::new(p, Integrator::Exact, 1e-4, 1, angle);
    let found = impacts(&mut cradle, 1.0 / 60.0, 0.9);
    // A pendulum released from 30 degrees reaches the bottom after a quarter
    // period K(sin 15 deg) / w0; there the striker meets the chain at L w.
    let quarter = elliptic_k((0.5 * angle).sin()) / p.w0();
    let w_bottom = (2.0 * p.mass * p.gravity * p.length * (1.0 - angle.cos()) / p.inertia()).sqrt();
    let first: Vec<&Impact> = found.iter().filter(|i| i.t < 2.0 * quarter).collect();
    // The striker's speed passes pair by pair through the resting chain.
    let pairs: Vec<usize> = first.iter().map(|i| i.pair).collect();
    assert_eq!(pairs, [0, 1, 2, 3]);
    for i in &first {
        // The root finder places impacts to 1e-14 s; 1e-12 s allows for the
        // closed-form flight's own round-off.
        assert!((i.t - quarter).abs() < 1e-12, "{} vs {quarter}", i.t);
        // Speeds to round-off of the closed form (1e-12 relative).
        assert!((i.speed - p.length * w_bottom).abs() < 1e-12, "{}", i.speed);
        assert!(i.contact.is_none());
    }
    // At the bottom, pair a touches at x = (2a + 1) r, one string length down.
    for i in &first {
        let x = (2 * i.pair + 1) as f64 * p.radius;
        assert!((i.at.0 - x).abs() < 1e-12 && (i.at.1 + p.length).abs() < 1e-12);
    }
    // Half a period later the last ball comes back and the speed runs the
    // other way through the chain.
    let back: Vec<usize> = found
        .iter()
        .filter(|i| (i.t - 3.0 * quarter).abs() < 1e-9)
        .map(|i| i.pair)
        .collect();
    assert_eq!(back, [3, 2, 1, 0]);
}

/// Every impact's course in `cradle` up to `until` (s), its snapshots `frame`
/// (s) apart.
fn courses(cradle: &mut Cradle, frame: f64, until: f64) -> Vec<Course> {
    cradle.record_impacts();
    cradle.record_courses(true);
    let mut all = Vec::new();
    let mut n = 1.0;
    while n * frame <= until {
        let s = cradle.snapshot(n * frame);
        all.extend(cradle.take_courses(s.t));
        n += 1.0;
    }
    all
}

#[test]
fn impacts_are_the_same_whatever_the_frame_rate() {
    for hertz in [false, true] {
        let p = steel(5, hertz);
        let run = |frame: f64| {
            let mut cradle = Cradle::new(p, Integrator::Exact, 1e-4, 2, 0.6);
            impacts(&mut cradle, frame, 2.0)
        };
        let (slow, fast) = (run(1.0 / 24.0), run(1.0 / 240.0));
        assert!(slow.len() > 8, "{hertz}: {}", slow.len());
        assert_eq!(slow, fast, "hertz {hertz}");
        let run = |frame: f64| {
            let mut cradle = Cradle::new(p, Integrator::Exact, 1e-4, 2, 0.6);
            courses(&mut cradle, frame, 2.0)
        };
        let (slow, fast) = (run(1.0 / 24.0), run(1.0 / 240.0));
        assert!(slow.len() > 4, "{hertz}: {}", slow.len());
        assert_eq!(slow, fast, "hertz {hertz}");
    }
}

#[test]
fn a_hertz_contact_passes_the_momentum_its_force_curve_integrates_to() {
    // Two balls, gravity a millionth of Earth's: the striker flies at a steady
    // 2 cm/s into the resting ball, so the pivots alone act beside the contact.
    // Elastic and viscoelastic contact (the exact engine), and with a trace of
    // air drag (the damped engine, which integrates the whole run).
    let air = 0.5 * 1.2 * 0.47 * std::f64::consts::PI * 0.02_f64.powi(2);
    for (dissipation, drag) in [(0.0, 0.0), (2e-6, 0.0), (2e-6, 1e-3 * air)] {
        let p = CradleParams {
            gravity: 9.81e-6,
            dissipation,
            drag,
            ..steel(2, true)
        };
        let v = 0.02;
        let (theta, omega) = ([-0.01, 0.0], [v / p.length, 0.0]);
        let start = || Cradle::from_state(p, Integrator::Exact, 1e-4, &theta, &omega);
        let found = courses(&mut start(), 0.1, 1.0);
        let [Course::Force { impact, curve }] = found.as_slice() else {
            panic!("one Hertz contact: {found:?}");
        };
        let contact = impact.contact.expect("a Hertz contact");
        // The state as the contact starts and as it ends.
        let mut again = start();
        let before = again.snapshot(impact.t);
        let after = again.snapshot(impact.t + contact.duration);
        // The ball at rest took the angular impulse I dw about its pivot
        // through the lever L (the line of centres is horizontal when both
        // hang straight down): the momentum exchanged along the line of
        // centres is I dw / L, and the striker lost as much. Tolerance: 1e-9
        // relative. The levers leave L by theta^2 / 2 as the balls move (1e-10
        // here), gravity's torque and the trace of drag add 1e-11 over the
        // contact, and the integration's own error is 1e-13 per step.
        let exchanged = p.inertia() * (after.omega[1] - before.omega[1]) / p.length;
        let lost = p.inertia() * (before.omega[0] - after.omega[0]) / p.length;
        for want in [exchanged, lost] {
            assert!(
                (contact.impulse / want - 1.0).abs() < 1e-9,
                "{dissipation} {drag}: impulse {} vs {want}",
                contact.impulse
            );
        }
        // Equal balls meeting at v: an elastic contact passes m v, a lossy one
        // less, and more than half of it (a restitution above 0).
        let elastic = p.mass * v;
        if dissipation == 0.0 {
            assert!((contact.impulse / elastic - 1.0).abs() < 1e-2);
        } else {
            assert!((0.5 * elastic..0.99 * elastic).contains(&contact.impulse));
        }
        // The curve: from the first touch back to 0 at the first point apart,
        // over the contact's duration; its trapezoid integral is the impulse
        // to the trapezoid rule's own error (~1e-4 at ~100 points). Elastic,
        // its highest point is the peak the report gives (the same step point).
        assert!(curve.len() > 50, "{}", curve.len());
        assert!(curve.windows(2).all(|w| w[1].0 > w[0].0));
        assert_eq!(curve[0].0, 0.0);
        assert_eq!(*curve.last().unwrap(), (contact.duration, 0.0));
        let peak = curve.iter().map(|c| c.1).fold(0.0, f64::max);
        if dissipation == 0.0 {
            assert!((peak / contact.peak_force - 1.0).abs() < 1e-12);
        }
        let trapezoid: f64 = curve
            .windows(2)
            .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
            .sum();
        assert!(
            (trapezoid / contact.impulse - 1.0).abs() < 1e-3,
            "{trapezoid}"
        );
    }
}

#[test]
fn an_ideal_impact_hands_the_striker_s_velocity_to_the_last_ball() {
    let p = steel(5, false);
    let angle = 30f64.to_radians();
    let mut cradle = Cradle::new(p, Integrator::Exact, 1e-4, 1, angle);
    let found = courses(&mut cradle, 1.0 / 60.0, 0.5);
    let Some(Course::Ideal { before, after, .. }) = found.first() else {
        panic!("an ideal impact: {found:?}");
    };
    // Equal elastic balls: the striker stops, the last ball leaves at the
    // striker's speed (to the closed form's round-off, 1e-12 relative).
    let v = p.release_speed(angle);
    let want_before = [v, 0.0, 0.0, 0.0, 0.0];
    let want_after = [0.0, 0.0, 0.0, 0.0, v];
    for (got, want) in [(before, want_before), (after, want_after)] {
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-12 * v, "{got:?} vs {want:?}");
        }
    }
}

#[test]
fn recording_impacts_and_courses_leaves_the_motion_as_it_was() {
    // The realistic cradle (viscoelastic contacts, drag) is integrated whole:
    // the impulses ride in its state, outside the error control.
    let mut p = steel(3, true);
    p.dissipation = 2e-6;
    p.drag = 0.5 * 1.2 * 0.47 * std::f64::consts::PI * p.radius * p.radius;
    let mut quiet = Cradle::new(p, Integrator::Exact, 1e-4, 1, 0.5);
    let mut heard = Cradle::new(p, Integrator::Exact, 1e-4, 1, 0.5);
    assert!(!courses(&mut heard, 0.05, 2.0).is_empty());
    assert_eq!(quiet.snapshot(2.0), heard.snapshot(2.0));
}

#[test]
fn a_hertz_contact_lasts_and_presses_as_hertz_theory_says() {
    let p = steel(2, true);
    let k = p.hertz.unwrap();
    let angle = 20f64.to_radians();
    let mut cradle = Cradle::new(p, Integrator::Exact, 1e-4, 1, angle);
    let found = impacts(&mut cradle, 1.0 / 60.0, 0.3);
    let first = found[0];
    let v = p.release_speed(angle);
    // The speed at the gap root is the release speed to the root's precision.
    assert!((first.speed - v).abs() < 1e-9 * v, "{} vs {v}", first.speed);
    let contact = first.contact.expect("a Hertz contact");
    // Johnson's two-sphere contact: reduced mass m/2 along the line of centres.
    // 2% covers what the formula leaves out: the balls swing on strings (their
    // inertia about the pivots is 0.6% above m L^2) under gravity, and the
    // contact's end is known to a step of the integration (~1 us in 150 us).
    let m = 0.5 * p.mass;
    let want = contact_time(k, m, v);
    assert!(
        (contact.duration / want - 1.0).abs() < 0.02,
        "{} vs {want}",
        contact.duration
    );
    let deepest = (1.25 * m * v * v / k).powf(0.4);
    let force = k * deepest.powf(1.5);
    assert!(
        (contact.peak_force / force - 1.0).abs() < 0.02,
        "{} vs {force}",
        contact.peak_force
    );
}

#[test]
fn a_hertz_chain_sounds_pair_by_pair_in_order() {
    let p = steel(5, true);
    let mut cradle = Cradle::new(p, Integrator::Exact, 1e-4, 1, 0.5);
    let found = impacts(&mut cradle, 1.0 / 60.0, 0.3);
    let pairs: Vec<usize> = found.iter().map(|i| i.pair).collect();
    assert_eq!(pairs, [0, 1, 2, 3]);
    // The touching chain is pressed pair by pair as the pulse runs down it (its
    // pairs meet at no speed: the first push compresses them at once), each
    // contact pressing about as hard as the strike and lasting longer the
    // further down the chain (the pulse spreads).
    for w in found.windows(2) {
        let lag = w[1].t - w[0].t;
        assert!((0.0..1e-4).contains(&lag), "{lag} {found:?}");
    }
    let contacts: Vec<_> = found.iter().map(|i| i.contact.unwrap()).collect();
    for c in &contacts[1..] {
        let ratio = c.peak_force / contacts[0].peak_force;
        assert!((0.5..1.0).contains(&ratio), "{ratio}");
        assert!(c.duration > contacts[0].duration);
    }
}

#[test]
fn a_lossy_cradle_meets_ever_slower() {
    let mut p = steel(3, true);
    p.dissipation = 2e-6;
    p.drag = 0.5 * 1.2 * 0.47 * std::f64::consts::PI * p.radius * p.radius;
    let mut cradle = Cradle::new(p, Integrator::Exact, 1e-4, 1, 0.5);
    let found = impacts(&mut cradle, 1.0 / 60.0, 4.0);
    let strikes: Vec<&Impact> = found.iter().filter(|i| i.speed > 0.05).collect();
    assert!(strikes.len() > 10, "{}", strikes.len());
    let (early, late) = (strikes[0].speed, strikes[strikes.len() - 1].speed);
    assert!(late < 0.95 * early, "{early} then {late}");
    assert!(found.iter().all(|i| i.contact.is_some()));
}

#[test]
fn a_stepped_cradle_finds_the_exact_impacts_to_its_step() {
    let p = steel(5, false);
    let exact = impacts(
        &mut Cradle::new(p, Integrator::Exact, 1e-4, 1, 0.5),
        0.01,
        1.0,
    );
    let stepped = impacts(
        &mut Cradle::new(p, Integrator::Verlet, 1e-4, 1, 0.5),
        0.01,
        1.0,
    );
    assert_eq!(exact.len(), stepped.len());
    for (e, s) in exact.iter().zip(&stepped) {
        assert_eq!(e.pair, s.pair);
        // Verlet's phase error over a second at dt = 1e-4 s is far below a step.
        assert!((e.t - s.t).abs() < 1e-4, "{} vs {}", e.t, s.t);
    }
}
