//! Property tests over random valid configs and random asset text.

use newtons_cradle::config::{Config, parse};
use newtons_cradle::physics::contact::{self, Resolution};
use newtons_cradle::physics::{Cradle, CradleParams, Integrator};
use proptest::prelude::*;

fn valid_config() -> impl Strategy<Value = Config> {
    (
        1usize..=12,
        0.0f64..=1.0,
        0.5f64..179.0,
        prop_oneof![Just(0.0), 0.0f64..0.01],
        prop_oneof![Just(1.0), 0.0f64..=1.0],
        0.005f64..0.05,
        1.5f64..8.0,
        prop_oneof![Just(9.81), 0.1f64..100.0],
    )
        .prop_map(|(balls, lift_frac, angle, gap, e, radius, len_ratio, g)| {
            let mut c = Config::default();
            c.cradle.balls = balls;
            c.cradle.radius = radius;
            c.cradle.length = radius * len_ratio;
            c.cradle.pivot_height = c.cradle.length + 2.0 * radius;
            c.cradle.rail_spread = 2.0 * radius;
            c.cradle.string_radius = radius / 20.0;
            c.cradle.gap = gap;
            c.cradle.gravity = g;
            c.start.lift = (lift_frac * balls as f64).round() as usize;
            c.start.angle_deg = angle;
            c.contact.restitution = e;
            c
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn energy_never_grows_and_nothing_panics(config in valid_config()) {
        prop_assert!(config.validate().is_ok(), "{:?}", config.validate());
        let mut cradle = Cradle::new(config.cradle_params(), Integrator::Exact, 1e-3, config.start.lift, config.lift_angle());
        let e0 = cradle.initial_energy();
        let mut last = e0;
        for n in 1..=80 {
            let s = cradle.snapshot(f64::from(n) * 0.025);
            prop_assert!(s.theta.iter().chain(&s.omega).all(|v| v.is_finite()), "non-finite state {:?}", s);
            let e = cradle.energy(&s);
            // Flights keep their energy to round-off and impulses with e <= 1 only
            // remove it: 1e-12 relative allows ~1e4 round-off steps of 1e-16.
            prop_assert!(e <= last + 1e-12 * e0, "energy grew: {} -> {} at t = {}", last, e, s.t);
            last = e.min(last);
        }
    }

    #[test]
    fn elastic_balls_never_overlap(mut config in valid_config()) {
        config.contact.restitution = 1.0;
        let p = config.cradle_params();
        let mut cradle = Cradle::new(p, Integrator::Exact, 1e-3, config.start.lift, config.lift_angle());
        for n in 1..=400 {
            let s = cradle.snapshot(f64::from(n) * 0.005);
            for a in 0..p.balls.saturating_sub(1) {
                let (x0, y0) = p.centre(a, s.theta[a]);
                let (x1, y1) = p.centre(a + 1, s.theta[a + 1]);
                let overlap = 2.0 * p.radius - (x1 - x0).hypot(y1 - y0);
                // Impacts are found to 1e-14 s at < 100 m/s: 1e-12 m, with room
                // for the round-off of the centres (~1e-17 m).
                prop_assert!(overlap < 1e-12, "pair {} overlaps {:e} m at t = {}", a, overlap, s.t);
            }
        }
    }

    #[test]
    fn fixed_step_integrators_stay_finite(config in valid_config(), which in 1usize..5) {
        let integrator = Integrator::ALL[which];
        let mut cradle = Cradle::new(config.cradle_params(), integrator, 1e-3, config.start.lift, config.lift_angle());
        let s = cradle.snapshot(1.0);
        prop_assert!(s.theta.iter().chain(&s.omega).all(|v| v.is_finite()));
    }

    #[test]
    fn no_ball_swings_higher_than_it_may(config in valid_config()) {
        let p = config.cradle_params();
        let (k, a) = (config.start.lift as f64, config.lift_angle());
        let mut cradle = Cradle::new(p, Integrator::Exact, 1e-3, config.start.lift, a);
        // Touching balls below the horizontal meet at equal angles, where an
        // impact between equal pendulums gives each a mix (1 -+ e)/2, (1 +- e)/2 of
        // the two speeds: no ball ever moves faster than the fastest did, so none
        // passes the initial angle. With gaps, or above the horizontal (where
        // touching balls can meet at different angles), the levers differ and
        // energy can gather in one ball (8 balls, 5 lifted to 157 deg, 5 mm gaps
        // sends one over the top), so there only the energy bounds the height:
        // sin^2(theta/2) <= k sin^2(A/2).
        let touching = p.gap == 0.0 && a < std::f64::consts::FRAC_PI_2;
        let height = |th: f64| (0.5 * th).sin().powi(2);
        let most = k * height(a);
        for n in 1..=200 {
            let s = cradle.snapshot(f64::from(n) * 0.01);
            for &th in &s.theta {
                if touching {
                    // 1e-9 rad: the round-off of flights restarted at each impact.
                    prop_assert!(th.abs() <= a + 1e-9, "{} rad past the initial {} at t = {}", th.abs(), a, s.t);
                } else {
                    prop_assert!(height(th) <= most * (1.0 + 1e-9) + 1e-15, "height {} past {} at t = {}", height(th), most, s.t);
                }
            }
        }
    }

    #[test]
    fn each_impact_pushes_the_pair_equally_and_oppositely(
        gap in prop_oneof![Just(0.0), 0.0f64..0.01],
        len_ratio in 1.5f64..8.0,
        ta in -1.5f64..1.5,
        dt in -0.2f64..0.2,
        wa in -20.0f64..20.0,
        wb in -20.0f64..20.0,
        e in 0.0f64..=1.0,
    ) {
        let p = CradleParams { balls: 2, radius: 0.02, mass: 0.26, length: 0.02 * len_ratio, gap, gravity: 9.81, restitution: e, hertz: None, dissipation: 0.0, drag: 0.0 };
        // Running the motion backwards turns a separating pair into an approaching one.
        let sign = contact::closing_speed(&p, (ta, wa), (ta + dt, wb)).signum();
        let (wa, wb) = (-sign * wa, -sign * wb);
        let (mut theta, mut omega) = (vec![ta, ta + dt], vec![wa, wb]);
        let before = contact::closing_speed(&p, (theta[0], omega[0]), (theta[1], omega[1]));
        prop_assume!(before < -1e-3 && (theta[0] - theta[1]).abs() > 1e-6);
        let (ja, jb) = contact::levers(&p, theta[0], theta[1]);
        let r = Resolution { restitution: e, rest_speed: 1e-9, touch: 1e-11 };
        contact::impact(&p, &r, &mut theta, &mut omega, 0);
        // The contact impulse P acts as -P on ball 0 and +P on ball 1 along the
        // normal: I dw0 = -P J0 and I dw1 = P J1, so dw0 / J0 + dw1 / J1 = 0, to
        // the round-off of a few operations on numbers of size |dw / J|.
        let (p0, p1) = ((omega[0] - wa) / ja, (omega[1] - wb) / jb);
        prop_assert!((p0 + p1).abs() <= 1e-12 * p0.abs().max(1.0), "{} vs {}", p0, p1);
        // And the pair separates at e times the speed it closed at.
        let after = contact::closing_speed(&p, (theta[0], omega[0]), (theta[1], omega[1]));
        prop_assert!((after + e * before).abs() <= 1e-12 * before.abs(), "{} after {}", after, before);
    }

    #[test]
    fn any_text_is_an_error_or_a_config_never_a_panic(text in "\\PC{0,200}") {
        let _ = parse(&text, "fuzz.ron");
    }

    #[test]
    fn ron_like_text_is_an_error_or_a_config_never_a_panic(
        text in "\\((cradle|start|render|lights|camera): ?\\(?(balls|lift|width|x)?:? ?(-?[0-9]{1,4}(\\.[0-9]+)?(e[0-9]{1,3})?|\\[|\\(|\\))*\\)?\\)?"
    ) {
        if let Ok(c) = parse(&text, "fuzz.ron") {
            prop_assert!(c.validate().is_ok());
        }
    }
}
