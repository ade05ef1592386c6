//! What the graphs read (the physics system's recording) against what
//! `simulate` prints at the same times, the CSV they export, and the momentum
//! both show.

use newtons_cradle::config::{Config, ContactModel};
use newtons_cradle::physics::Course;
use newtons_cradle::scene::CradleWorld;
use newtons_cradle::scene::record::{SPAN, csv};
use serde_json::Value;

/// `simulate`'s sample lines for `config` over `duration` s every `every` s.
fn simulated(config: &Config, duration: f64, every: f64) -> Vec<Value> {
    let mut out = Vec::new();
    newtons_cradle::simulate::simulate(config, duration, every, false, &mut out).expect("runs");
    String::from_utf8(out)
        .expect("utf-8")
        .lines()
        .map(|l| serde_json::from_str::<Value>(l).expect("JSON"))
        .filter(|v| v.get("t").is_some())
        .collect()
}

/// Relative difference, against the larger of the two magnitudes or `floor`.
fn rel(a: f64, b: f64, floor: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(floor)
}

#[test]
fn the_recorded_series_are_simulates_at_the_same_times() {
    for hertz in [false, true] {
        let mut config = Config::default();
        config.start.lift = 2;
        config.start.angle_deg = 40.0;
        if hertz {
            config.contact.model = ContactModel::Hertz;
        }
        let mut world = CradleWorld::new(&config);
        world.set_recording(true);
        let every = 0.01;
        for n in 1..=300 {
            world.show_at(f64::from(n) * every);
        }
        let rec = world.recording();
        assert_eq!(rec.samples.len(), 300);
        let lines = simulated(&config, 3.0, every);
        let p = config.cradle_params();
        // The same engine queried at the same times gives the same states; 1e-12
        // allows for the order of the sums (energy and momentum over balls).
        // Momentum passes through 0 twice a swing: compared against the
        // swing's largest, m times the release speed.
        let p_scale = p.mass * p.release_speed(config.start.angle_deg.to_radians());
        for s in &rec.samples {
            let line = lines
                .iter()
                .find(|l| l["t"].as_f64() == Some(s.t))
                .expect("simulate samples the same time");
            let e = line["energy"].as_f64().unwrap();
            assert!(
                rel(s.total, e, 0.0) < 1e-12,
                "t {}: {} vs {e}",
                s.t,
                s.total
            );
            let m = line["momentum"].as_f64().unwrap();
            assert!(rel(s.total_momentum(), m, p_scale) < 1e-12, "t {}", s.t);
            for (a, b) in s.theta.iter().zip(line["theta"].as_array().unwrap()) {
                assert!(rel(*a, b.as_f64().unwrap(), 1.0) < 1e-12, "t {}", s.t);
            }
        }
        assert!(!rec.impacts.is_empty(), "impacts recorded too");
    }
}

#[test]
fn simulates_momentum_is_the_balls_horizontal_momentum() {
    let config = Config::default();
    let p = config.cradle_params();
    for line in simulated(&config, 1.0, 0.05) {
        let theta = line["theta"].as_array().unwrap();
        let omega = line["omega"].as_array().unwrap();
        // m times each centre's horizontal speed, L cos(theta) omega.
        let want: f64 = theta
            .iter()
            .zip(omega)
            .map(|(t, w)| p.mass * p.length * t.as_f64().unwrap().cos() * w.as_f64().unwrap())
            .sum();
        let got = line["momentum"].as_f64().unwrap();
        assert!((got - want).abs() <= 1e-15, "{got} vs {want}");
    }
}

#[test]
fn the_graphs_keep_their_span_forget_another_cradle_and_record_nothing_closed() {
    let config = Config::default();
    let mut world = CradleWorld::new(&config);
    world.show_at(0.5);
    assert!(world.recording().samples.is_empty(), "closed: nothing");
    world.set_recording(true);
    for n in 1..=400 {
        world.show_at(f64::from(n) * 0.1);
    }
    let rec = world.recording();
    let (first, last) = (rec.samples[0].t, rec.samples.back().unwrap().t);
    assert!(
        last - first <= SPAN && last - first > SPAN - 0.2,
        "{first}..{last}"
    );
    // A paused frame (the same time) adds nothing.
    let len = rec.samples.len();
    world.show_at(40.0);
    assert_eq!(world.recording().samples.len(), len);
    // A new cradle at t = 0: what was recorded was another's.
    world.respawn(&config);
    world.show_at(0.1);
    assert_eq!(world.recording().samples.len(), 1);
}

#[test]
fn the_last_impact_shows_its_course_while_the_graphs_are_open() {
    for hertz in [false, true] {
        let mut config = Config::default();
        if hertz {
            config.contact.model = ContactModel::Hertz;
        }
        let p = config.cradle_params();
        let v = p.release_speed(config.start.angle_deg.to_radians());
        let mut world = CradleWorld::new(&config);
        world.set_recording(true);
        // Past the first strike (a quarter period), before the second.
        for n in 1..=30 {
            world.show_at(f64::from(n) / 60.0);
        }
        let strike = &world.recording().strike;
        if hertz {
            // The pulse runs down the chain: one force curve per pair, each
            // rising from the first touch and back to 0, passing about the
            // striker's momentum m v on (the chain's pairs pass a little more
            // or less, 20% allows for it).
            let pairs: Vec<usize> = strike
                .iter()
                .map(|c| match c {
                    Course::Force { impact, curve } => {
                        assert!(curve.len() > 20 && curve.iter().all(|&(_, f)| f >= 0.0));
                        assert!(curve.iter().any(|&(_, f)| f > 100.0), "{curve:?}");
                        assert_eq!(curve.last().unwrap().1, 0.0);
                        let impulse = impact.contact.unwrap().impulse;
                        assert!((impulse / (p.mass * v) - 1.0).abs() < 0.2, "{impulse}");
                        impact.pair
                    }
                    Course::Ideal { .. } => panic!("a Hertz contact: {c:?}"),
                })
                .collect();
            assert_eq!(pairs, [0, 1, 2, 3]);
        } else {
            // Equal elastic balls: the striker's velocity passes to the last.
            let [Course::Ideal { before, after, .. }] = strike.as_slice() else {
                panic!("one ideal impact: {strike:?}");
            };
            assert!((before[0] - v).abs() < 1e-9 && before[4] == 0.0);
            assert!((after[4] - v).abs() < 1e-9 && after[0].abs() < 1e-9);
        }
        // Closed, the physics keeps no courses.
        world.set_recording(false);
        for n in 31..=90 {
            world.show_at(f64::from(n) / 60.0);
            assert!(world.impacts().courses.is_empty());
        }
        assert!(world.recording().strike.is_empty());
    }
}

#[test]
fn the_csv_has_a_header_and_a_row_per_recorded_frame() {
    let mut config = Config::default();
    config.cradle.balls = 3;
    let mut world = CradleWorld::new(&config);
    world.set_recording(true);
    for n in 1..=20 {
        world.show_at(f64::from(n) * 0.05);
    }
    let text = csv(world.recording());
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows.len(), 21);
    let header: Vec<&str> = rows[0].split(',').collect();
    // Time, energy, its error, the two losses, momentum; then five per ball.
    assert_eq!(header.len(), 6 + 5 * 3);
    assert_eq!(header[0], "t_s");
    assert!(header.contains(&"ball3_amplitude_rad"));
    for (n, row) in rows[1..].iter().enumerate() {
        let cells: Vec<f64> = row
            .split(',')
            .map(|c| c.parse().expect("a number"))
            .collect();
        assert_eq!(cells.len(), header.len());
        assert_eq!(cells[0], (n + 1) as f64 * 0.05);
    }
}
