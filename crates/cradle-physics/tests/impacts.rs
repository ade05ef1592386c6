//! The impacts the engines report: when, which pair, how fast, where, and for
//! Hertz contact how long and how hard; the same at any frame rate.

mod common;

use cradle_physics::hertz::contact_time;
use cradle_physics::{Cradle, CradleParams, Impact, Integrator};

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
    }
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
