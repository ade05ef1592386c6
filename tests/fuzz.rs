//! Fuzz-style properties of the loader and validation: mutated copies of the
//! shipped asset and random override flags never panic, are accepted or refused
//! (exit 0 or 2), and every accepted config simulates one second in bounded time.

mod common;

use newtons_cradle::cli::Common;
use newtons_cradle::config::{Config, DEFAULT_ASSET, parse};
use proptest::prelude::*;
use std::sync::mpsc;
use std::time::Duration;

/// Byte ranges of the number literals of `src` (outside `//` comments).
fn numbers(src: &str) -> Vec<(usize, usize)> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
            continue;
        }
        let starts = (b[i].is_ascii_digit()
            || (b[i] == b'-' && b.get(i + 1).is_some_and(u8::is_ascii_digit)))
            && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'));
        if starts {
            let s = i;
            i += 1;
            while i < b.len()
                && (b[i].is_ascii_digit() || matches!(b[i], b'.' | b'e' | b'E' | b'+' | b'-'))
            {
                i += 1;
            }
            out.push((s, i));
        } else {
            i += 1;
        }
    }
    out
}

/// Values an adversary would write.
const HOSTILE: [&str; 16] = [
    "0",
    "-0.0",
    "-1",
    "1e300",
    "-1e300",
    "1e-300",
    "2.5",
    "99999999999999999999",
    "NaN",
    "inf",
    "179.9999999",
    "1e4",
    "1e13",
    "0.0000001",
    "256",
    "8193",
];

/// One edit of the asset text.
#[derive(Debug, Clone)]
enum Edit {
    /// Replace number literal `k % count` by a hostile value or a random float.
    Number(usize, String),
    /// Insert a character at `k % len`.
    Insert(usize, char),
    /// Delete the character at `k % len`.
    Delete(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    let value = prop_oneof![
        prop::sample::select(HOSTILE.to_vec()).prop_map(str::to_owned),
        any::<f64>().prop_map(|v| format!("{v:?}")),
        (-1000i64..1000).prop_map(|v| v.to_string()),
    ];
    prop_oneof![
        (any::<usize>(), value).prop_map(|(k, v)| Edit::Number(k, v)),
        (
            any::<usize>(),
            prop::sample::select(vec!['(', ')', ',', ':', '.', '-', 'x', '"', '\u{feff}'])
        )
            .prop_map(|(k, c)| Edit::Insert(k, c)),
        any::<usize>().prop_map(Edit::Delete),
    ]
}

/// The shipped asset with `edits` applied.
fn mutate(edits: &[Edit]) -> String {
    let mut src = DEFAULT_ASSET.to_owned();
    for e in edits {
        let chars: Vec<(usize, char)> = src.char_indices().collect();
        match e {
            Edit::Number(k, v) => {
                let nums = numbers(&src);
                if let Some(&(s, t)) = nums.get(k % nums.len().max(1)) {
                    src.replace_range(s..t, v);
                }
            }
            Edit::Insert(k, c) => {
                let at = chars.get(k % chars.len().max(1)).map_or(0, |&(i, _)| i);
                src.insert(at, *c);
            }
            Edit::Delete(k) => {
                if let Some(&(i, _)) = chars.get(k % chars.len().max(1)) {
                    src.remove(i);
                }
            }
        }
    }
    src
}

fn flags() -> impl Strategy<Value = Common> {
    (
        prop::option::of(-5i64..300),
        prop::option::of(-2i64..250),
        prop::option::of(prop_oneof![-10.0..200.0, Just(179.999_999), Just(1e300)]),
        prop::option::of(prop_oneof![-1.0..20.0, Just(0.0)]),
        prop::option::of(prop_oneof![-1.0..1.0, Just(1e-7), Just(1e-9)]),
        prop::option::of(-2i64..300),
        prop::option::of(0i64..10_000),
    )
        .prop_map(|(balls, lift, angle, gap, dt, threads, width)| Common {
            balls,
            lift,
            angle,
            gap,
            dt,
            threads,
            width,
            ..Common::default()
        })
}

/// Simulates one second of `config` on another thread; false if it takes longer
/// than `limit` (the thread is left to finish on its own).
fn simulates_within(config: &Config, limit: Duration) -> bool {
    let config = config.clone();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut cradle = config.build_cradle();
        let s = cradle.snapshot(1.0);
        let finite =
            cradle.energy(&s).is_finite() && s.theta.iter().chain(&s.omega).all(|x| x.is_finite());
        tx.send(finite).ok();
    });
    rx.recv_timeout(limit) == Ok(true)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn mutated_assets_and_flags_are_accepted_or_refused_never_stuck(
        edits in prop::collection::vec(edit(), 1..4),
        common in flags(),
    ) {
        let src = mutate(&edits);
        // A panic here fails the property; an error is a refusal (exit 2).
        let Ok(mut config) = parse(&src, "fuzz.ron") else { return Ok(()) };
        if common.apply(&mut config).is_err() {
            return Ok(());
        }
        // Generous: the stiffest accepted contact takes ~10 s a simulated second.
        prop_assert!(
            simulates_within(&config, Duration::from_mins(1)),
            "accepted but did not simulate one second: {src}\n{common:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]

    #[test]
    fn the_binary_exits_0_or_2_for_mutated_assets(edits in prop::collection::vec(edit(), 1..3)) {
        let dir = common::temp_dir("fuzz-bin");
        let path = dir.join("fuzz.ron");
        std::fs::write(&path, mutate(&edits)).expect("write");
        let o = common::run(&[
            "simulate", "--duration", "0", "--config", path.to_str().expect("utf-8"),
        ]);
        let code = o.status.code();
        prop_assert!(code == Some(0) || code == Some(2), "{code:?}: {}", common::stderr(&o));
        prop_assert!(!common::stderr(&o).contains("panicked"), "{}", common::stderr(&o));
    }
}

#[test]
fn the_mutations_reach_the_assets_numbers_and_some_are_accepted() {
    let nums = numbers(DEFAULT_ASSET);
    assert!(nums.len() > 40, "{} numbers found", nums.len());
    // Replacing a number with a valid one keeps the asset valid; with a hostile
    // one, refuses it; so the property above sees both kinds.
    let mut accepted = 0;
    for k in 0..nums.len() {
        if parse(&mutate(&[Edit::Number(k, "1".to_owned())]), "t.ron").is_ok() {
            accepted += 1;
        }
    }
    assert!(accepted > 5, "{accepted} of {} accepted", nums.len());
    assert!(parse(&mutate(&[Edit::Number(0, "NaN".to_owned())]), "t.ron").is_err());
}

#[test]
fn hertz_contact_at_the_extremes_always_finishes() {
    // Every corner of the accepted ranges that make contacts short, stiff,
    // light, heavy, fast or slow: radius, Young's modulus, dissipation (none,
    // or the most this cradle takes), density, gravity and lift angle. Each
    // case simulates one second on its own thread; a case not done in a minute
    // has hung (the slowest takes about a second on the 2-core build machine).
    let mut cases = 0;
    for radius in [1e-4, 0.02] {
        for youngs in [1e5, 1e13] {
            for damped in [false, true] {
                for density in [1.0, 1e5] {
                    for gravity in [1e-3, 1e4] {
                        for angle in [1.0, 90.0, 179.999] {
                            let mut c = Config::default();
                            c.cradle.radius = radius;
                            c.cradle.string_radius = 0.03 * radius;
                            c.cradle.rail_spread = 2.5 * radius;
                            c.cradle.density = density;
                            c.cradle.gravity = gravity;
                            c.contact.model = newtons_cradle::config::ContactModel::Hertz;
                            c.contact.youngs_modulus = youngs;
                            c.start.angle_deg = angle;
                            if damped {
                                c.contact.dissipation = c.dissipation_limit().0.min(1e-3);
                            }
                            assert!(c.validate().is_ok(), "{c:?}");
                            assert!(
                                simulates_within(&c, Duration::from_mins(1)),
                                "did not simulate one second: r {radius}, E {youngs}, A {}, \
                                 density {density}, g {gravity}, angle {angle}",
                                c.contact.dissipation
                            );
                            cases += 1;
                        }
                    }
                }
            }
        }
    }
    assert_eq!(cases, 96);
}
