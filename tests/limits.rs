//! Accepted input finishes in time proportional to its work, or is refused with
//! its range; long work talks while it runs.

mod common;

use common::{run, stderr};
use std::io::{BufRead, BufReader, Read};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

#[test]
fn values_that_would_hang_or_lose_precision_are_refused_with_their_range() {
    for (asset, want) in [
        (
            "(cradle: (gravity: 1e30))",
            ["cradle.gravity", "1e-3..=1e4"],
        ),
        ("(cradle: (radius: 1e-20))", ["cradle.radius", "1e-4..=10"]),
        ("(cradle: (density: 1e-300))", ["cradle.density", "1..=1e5"]),
        (
            "(contact: (model: hertz, youngs_modulus: 1e30))",
            ["contact.youngs_modulus", "1e5..=1e13"],
        ),
        (
            "(start: (angle_deg: 179.999999))",
            ["start.angle_deg", "0..=179.999"],
        ),
        (
            "(camera: (position: (0.0, 0.1, 1e5)))",
            ["camera.position", "+-10 (m)"],
        ),
        (
            "(camera: (position: (0.0, 0.36, 0.6), look_at: (0.0, 0.36, 0.6000001)))",
            ["camera.look_at", "1e-3 m"],
        ),
        (
            "(lights: [Directional(direction: (1e-30, -1e-30, 0.0), color: (1.0, 1.0, 1.0), intensity: 1.0)])",
            ["lights[0].direction", "1e-6"],
        ),
        (
            "(lights: [Point(position: (1e30, 1.0, 0.0), color: (1.0, 1.0, 1.0), intensity: 1.0)])",
            ["lights[0].position", "+-10000"],
        ),
    ] {
        let e = newtons_cradle::config::parse(asset, "t.ron")
            .expect_err(asset)
            .to_string();
        assert!(want.iter().all(|w| e.contains(w)), "{asset}: {e}");
    }
}

#[test]
fn the_hardest_accepted_cradles_finish() {
    // The fastest pendulum the ranges allow (1e-4 m balls under 1e4 m/s^2), with
    // 199 of 200 balls at the largest angle: one simulated second in bounded work.
    let o = run(&[
        "simulate",
        "--duration",
        "1",
        "--every",
        "1",
        "--balls",
        "200",
        "--lift",
        "199",
        "--angle",
        "179.999",
        "--config",
        "tests/data/fastest.ron",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let summary = String::from_utf8_lossy(&o.stdout)
        .lines()
        .last()
        .map(str::to_owned)
        .expect("a summary");
    let v: serde_json::Value = serde_json::from_str(&summary).expect("JSON");
    let err = v["summary"]["max_energy_rel_error"]
        .as_f64()
        .expect("a number, never null");
    // Exact impacts: round-off over some 50,000 of them.
    assert!(err < 1e-9, "{err}");
}

#[test]
fn a_long_simulation_streams_its_lines_and_says_how_long_it_will_take() {
    // RK4 at 1e-7 s over 1e6 s would take weeks: lines must arrive anyway, and
    // stderr must say how long the rest will take.
    let mut child = Command::new(env!("CARGO_BIN_EXE_newtons-cradle"))
        .args(["simulate", "--integrator", "rk4", "--dt", "1e-7"])
        .args(["--duration", "1e6", "--every", "1"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starts");
    let out = child.stdout.take().expect("stdout");
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                return;
            }
        }
    });
    // Generous: each sample takes a fraction of a second; a buffered stream would
    // hold these for minutes.
    let first: Vec<String> = (0..5)
        .map_while(|_| rx.recv_timeout(Duration::from_mins(2)).ok())
        .collect();
    child.kill().ok();
    let mut err = String::new();
    child
        .stderr
        .take()
        .expect("stderr")
        .read_to_string(&mut err)
        .ok();
    child.wait().ok();
    assert_eq!(first.len(), 5, "lines while the run goes on: {first:?}");
    assert!(first[0].starts_with("{\"params\""), "{}", first[0]);
    assert!(err.contains("will take about"), "{err}");
}

#[test]
fn flags_a_benchmark_does_not_use_are_named() {
    let o = run(&[
        "bench",
        "physics",
        "--balls",
        "7",
        "--dt",
        "1e-3",
        "--duration",
        "0.1",
        "--min-dt",
        "1e-2",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("--balls, --dt not used"), "{e}");
}

#[test]
fn the_stress_suite_says_which_scenario_runs() {
    let o = run(&["bench", "stress", "--json", "--scale", "0.01"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("stress 1/") && e.contains("200 balls"), "{e}");
}

#[test]
fn a_coarse_every_still_says_how_long_the_run_will_take() {
    // One sample at the start and the next weeks away (RK4 at 1e-7 s to
    // t = 1e6 s): the physics reports its progress between samples, so the
    // estimate comes within seconds, not with the second sample.
    let mut child = Command::new(env!("CARGO_BIN_EXE_newtons-cradle"))
        .args(["simulate", "--integrator", "rk4", "--dt", "1e-7"])
        .args(["--duration", "1e6", "--every", "1e6"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starts");
    let err = child.stderr.take().expect("stderr");
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                return;
            }
        }
    });
    // Generous: the estimate comes after 1 s of work.
    let said = std::iter::from_fn(|| rx.recv_timeout(Duration::from_mins(1)).ok())
        .find(|l| l.contains("will take about"));
    child.kill().ok();
    child.wait().ok();
    assert!(said.is_some(), "no estimate");
}
