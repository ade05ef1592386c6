//! A cradle that loses energy, end to end: elastic runs print exactly what they
//! printed before dissipation existed, the realistic asset ends in phase, the
//! dissipation keys refuse what they cannot do, and `bench rocking` reports.

mod common;

use common::{lines, run, stderr, temp_dir};
use newtons_cradle::bench::rocking::{self, IN_PHASE};
use newtons_cradle::config::load_file;
use std::path::Path;

/// The JSON of a run with `wall_seconds` (the one field that differs run to
/// run) zeroed.
fn without_wall_time(stdout: &[u8]) -> String {
    let text = String::from_utf8(stdout.to_vec()).expect("utf-8");
    let at = text.find("\"wall_seconds\":").expect("a summary");
    let end = at + text[at..].find('}').expect("closed");
    format!("{}\"wall_seconds\":0{}", &text[..at], &text[end..])
}

#[test]
fn zero_dissipation_and_drag_print_the_elastic_hertz_json_byte_for_byte() {
    // tests/data/hertz_elastic.jsonl is the elastic run as the program writes
    // it, from the same command; zero dissipation and drag (the default
    // asset's) must keep it byte for byte. It was written before the
    // dissipation keys existed and written again when the exact engine began
    // to count time from an epoch at each event: every angle and speed moved
    // by at most 3.6e-11 (the Hertz phases' tolerance), the same 64 contacts.
    // The samples' momentum was added since: every other byte is as it was.
    let o = run(&[
        "simulate",
        "--contact",
        "hertz",
        "--duration",
        "3",
        "--every",
        "0.05",
        "--lift",
        "2",
        "--angle",
        "25",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let want = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/hertz_elastic.jsonl"),
    )
    .expect("the stored run");
    assert!(
        without_wall_time(&o.stdout) == want,
        "the elastic run changed"
    );
}

#[test]
fn the_realistic_asset_breaks_up_and_ends_swinging_in_phase() {
    // The whole 90 s the issue asks for: 0.7 s of CPU in a release build.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/presets/realistic.ron");
    let config = load_file(&path).expect("the shipped asset loads");
    let r = rocking::run(&config, 90.0);
    // The break-up: a second after release (one strike), more than the two end
    // balls swing (by over a tenth of a degree).
    let (_, after_strike) = r
        .amplitudes
        .iter()
        .find(|(t, _)| *t >= 1.0)
        .expect("sampled");
    let moving = after_strike.iter().filter(|&&a| a > 0.1).count();
    assert!(moving >= 3, "{after_strike:?}");
    // In phase by the end, and staying so: the last swing's spread is small
    // against the common amplitude, which is still there (the motion has not
    // died: at least 2 degrees).
    assert!(r.in_phase_from.is_some(), "never in phase: {r:?}");
    assert!(r.final_spread <= IN_PHASE * r.final_amplitude, "{r:?}");
    assert!(r.final_amplitude.to_degrees() > 2.0, "{r:?}");
    // Where the energy went: both ways, and it adds up to 1e-8 of the start.
    assert!(r.lost[0] > 0.0 && r.lost[1] > 0.0, "{:?}", r.lost);
    let balance = (r.energy[1] + r.lost[0] + r.lost[1] - r.energy[0]) / r.energy[0];
    assert!(balance.abs() < 1e-8, "{balance:e}");
}

#[test]
fn simulate_books_the_energy_lost_when_the_cradle_dissipates() {
    let o = run(&[
        "simulate",
        "--config",
        "assets/presets/realistic.ron",
        "--duration",
        "2",
        "--every",
        "0.5",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = lines(&o);
    assert_eq!(v[0]["params"]["dissipation"], 5e-7);
    assert_eq!(v[0]["params"]["air_density"], 1.2);
    let mut last = f64::INFINITY;
    for s in &v[1..v.len() - 1] {
        let e = s["energy"].as_f64().expect("energy");
        assert!(e <= last, "energy grew at {}", s["t"]);
        last = e;
        assert_eq!(s["lost"].as_array().map(Vec::len), Some(2));
    }
    let summary = &v.last().unwrap()["summary"];
    assert!(summary["lost_contact"].as_f64().is_some_and(|x| x > 0.0));
    assert!(summary["lost_drag"].as_f64().is_some_and(|x| x > 0.0));
    // With dissipation the error is that of the energy balance.
    assert!(
        summary["max_energy_rel_error"]
            .as_f64()
            .is_some_and(|e| e < 1e-8)
    );
}

#[test]
fn dissipation_keys_refuse_what_they_cannot_do_with_exit_2() {
    let dir = temp_dir("dissipation-keys");
    let cases = [
        (
            "(contact: (dissipation: 1e-6))",
            "contact.dissipation",
            "contact.model hertz",
        ),
        (
            "(contact: (model: hertz, dissipation: 0.1))",
            "contact.dissipation",
            "0..=1e-3",
        ),
        (
            "(contact: (model: hertz), cradle: (air_density: 1.2), physics: (integrator: rk4))",
            "cradle.air_density",
            "physics.integrator exact",
        ),
        (
            "(cradle: (drag_coefficient: -1.0))",
            "cradle.drag_coefficient",
            "0..=10",
        ),
        // Tiny, stiff balls damped ten million times longer than they touch:
        // outside the viscoelastic model (such contacts once never ended).
        (
            "(cradle: (radius: 1e-4, string_radius: 1e-6), \
             contact: (model: hertz, dissipation: 1e-3, youngs_modulus: 1e13))",
            "contact.dissipation",
            "a tenth of its shortest contact",
        ),
    ];
    for (i, (text, key, allowed)) in cases.iter().enumerate() {
        let path = dir.join(format!("c{i}.ron"));
        std::fs::write(&path, text).expect("write");
        let o = run(&[
            "simulate",
            "--config",
            path.to_str().unwrap(),
            "--duration",
            "1",
        ]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(key) && err.contains(allowed), "{text}: {err}");
    }
}

#[test]
fn bench_rocking_reports_phase_energy_and_restitution() {
    let o = run(&[
        "bench",
        "rocking",
        "--config",
        "assets/presets/realistic.ron",
        "--duration",
        "3",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = &lines(&o)[0];
    let e = v["restitution"].as_array().expect("restitution");
    assert_eq!(e.len(), 3);
    assert!(
        e.iter()
            .all(|p| p[1].as_f64().is_some_and(|x| (0.9..1.0).contains(&x)))
    );
    let bad = run(&["bench", "rocking", "--duration", "0"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(stderr(&bad).contains("1..=3600"), "{}", stderr(&bad));
    // Ideal impacts have no contact to measure: refused, not reported as a
    // restitution of -0.79 with nothing lost.
    let ideal = run(&["bench", "rocking", "--duration", "3", "--contact", "ideal"]);
    assert_eq!(ideal.status.code(), Some(2), "{}", stderr(&ideal));
    let err = stderr(&ideal);
    assert!(
        err.contains("contact.model") && err.contains("allowed: hertz"),
        "{err}"
    );
}

#[test]
fn the_dissipation_limit_is_a_tenth_of_the_shortest_hertz_contact() {
    use newtons_cradle::config::{Config, ContactModel, MAX_ANGLE_DEG};
    let mut c = Config::default();
    c.contact.model = ContactModel::Hertz;
    let (most, shortest) = c.dissipation_limit();
    // Johnson's duration of a Hertz impact, in its textbook form:
    // 2.868 (m^2 / (R E^2 v))^(1/5), with R = r/2, E = E/(2 (1 - nu^2)), m the
    // reduced mass of two pendulums (I / L^2 each), v twice the speed of a
    // ball let go from the top.
    let (r, l, g) = (c.cradle.radius, c.cradle.length, c.cradle.gravity);
    let mass = c.ball_mass();
    let inertia = mass * (l * l + 0.4 * r * r);
    let w0 = (mass * g * l / inertia).sqrt();
    let v = 2.0 * 2.0 * l * w0 * (0.5 * MAX_ANGLE_DEG.to_radians()).sin();
    let m = 0.5 * inertia / (l * l);
    let e = c.contact.youngs_modulus / (2.0 * (1.0 - c.contact.poisson_ratio.powi(2)));
    let want = 2.868 * (m * m / (0.5 * r * e * e * v)).powf(0.2);
    // The constants 2.868 and 2.94 * (15/16)^0.4 agree to 0.1%.
    assert!(
        (shortest / want - 1.0).abs() < 5e-3,
        "{shortest} against {want}"
    );
    assert_eq!(most, 0.1 * shortest);
    // The realistic preset's 5e-7 s is far inside (the limit is ~1.4e-5 s).
    assert!(5e-7 < most && most < 1e-4, "{most}");
}
