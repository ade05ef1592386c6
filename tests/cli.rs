//! The binary's contracts (DESIGN.md): exit codes, located messages, the JSON Lines
//! of `simulate`, and which asset is used.

mod common;

use common::{lines, run, run_in, stderr, temp_dir};
use std::path::Path;
use std::process::Command;

#[test]
fn bad_flags_exit_2_with_the_valid_range() {
    let cases: [(&[&str], &str); 12] = [
        (
            &["--balls", "0"],
            "--balls 0: not allowed; allowed: 1..=200",
        ),
        (
            &["--balls", "-3"],
            "--balls -3: not allowed; allowed: 1..=200",
        ),
        (&["--lift", "6"], "--lift 6: not allowed; allowed: 0..=5"),
        (
            &["--angle", "180"],
            "--angle 180: not allowed; allowed: 0..=179.999",
        ),
        (
            &["--gap", "-0.01"],
            "--gap -0.01: not allowed; allowed: 0..=10",
        ),
        (&["--dt", "0"], "--dt 0: not allowed; allowed: 1e-7..=0.1"),
        (
            &["--threads", "-1"],
            "--threads -1: not allowed; allowed: 0..=256",
        ),
        (
            &["--width", "4"],
            "--width 4: not allowed; allowed: 16..=8192",
        ),
        (&["--every", "0"], "--every 0: not allowed; allowed: > 0"),
        (
            &["--every", "abc"],
            "--every abc: not a number; allowed: > 0",
        ),
        (
            &["--every", "inf"],
            "--every inf: not allowed; allowed: > 0",
        ),
        (
            &["--duration", "-1"],
            "--duration -1: not allowed; allowed: 0..=1e7",
        ),
    ];
    for (flags, want) in cases {
        let mut args = vec!["simulate"];
        args.extend_from_slice(flags);
        if !flags.contains(&"--duration") {
            args.extend_from_slice(&["--duration", "0.1"]);
        }
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{flags:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(want), "{flags:?}: {}", stderr(&o));
        assert!(o.stdout.is_empty(), "nothing on stdout for bad input");
    }
    let o = run(&["simulate", "--balls", "many"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--balls"));
}

#[test]
fn bad_config_files_exit_2_with_file_line_and_column() {
    let dir = temp_dir("bad");
    let cases: [(&str, &[u8], &str); 5] = [
        (
            "range.ron",
            b"(\n  start: (\n    angle_deg: 1e400,\n  ),\n)\n",
            "range.ron:3:5: `start.angle_deg` is inf; allowed: a finite number",
        ),
        (
            "typo.ron",
            b"(cradle: (bals: 3))",
            "typo.ron:1:11: Unexpected field named `bals`",
        ),
        ("empty.ron", b"", "empty.ron:1:1"),
        (
            "binary.ron",
            &[0xde, 0xad, 0xbe, 0xef, 0xff, 0x00],
            "binary.ron: the config is not UTF-8 text",
        ),
        ("missing.ron", b"", "missing.ron: cannot read the config"),
    ];
    for (name, content, want) in cases {
        let path = dir.join(name);
        if name != "missing.ron" {
            std::fs::write(&path, content).expect("write");
        }
        let o = run(&["simulate", "--config", path.to_str().expect("utf-8 path")]);
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        assert!(stderr(&o).contains(want), "{name}: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"));
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn simulate_prints_params_samples_and_summary() {
    let o = run(&[
        "simulate",
        "--duration",
        "2",
        "--every",
        "0.1",
        "--balls",
        "4",
        "--lift",
        "2",
        "--gap",
        "0.001",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = lines(&o);
    assert_eq!(
        v.len(),
        1 + 21 + 1,
        "params, samples at 0, 0.1, .., 2.0, summary"
    );
    let p = &v[0]["params"];
    for key in [
        "balls",
        "radius",
        "length",
        "gap",
        "gravity",
        "mass",
        "lift",
        "angle_deg",
        "contact",
        "integrator",
        "dt",
    ] {
        assert!(!p[key].is_null(), "params.{key}");
    }
    assert_eq!(p["balls"], 4);
    assert_eq!(p["gap"], 0.001);
    assert_eq!(p["contact"], "ideal");
    assert_eq!(p["integrator"], "exact");
    let mut last_collisions = 0;
    for (n, s) in v[1..v.len() - 1].iter().enumerate() {
        // A product, not a running sum: exactly n * 0.1 in f64.
        assert_eq!(s["t"].as_f64(), Some(n as f64 * 0.1));
        assert_eq!(s["theta"].as_array().map(Vec::len), Some(4));
        assert_eq!(s["omega"].as_array().map(Vec::len), Some(4));
        let c = s["collisions"].as_u64().expect("count");
        assert!(c >= last_collisions);
        last_collisions = c;
    }
    let sum = &v[v.len() - 1]["summary"];
    assert_eq!(sum["duration"], 2.0);
    assert_eq!(sum["collisions"].as_u64(), Some(last_collisions));
    assert!(last_collisions > 0);
    assert!(sum["max_energy_rel_error"].as_f64().expect("number") < 1e-12);
    for key in ["energy_initial", "energy_final", "wall_seconds"] {
        assert!(sum[key].is_number(), "summary.{key}");
    }
}

#[test]
fn samples_end_at_the_duration_within_rounding() {
    // 3 * 0.1 = 0.30000000000000004 > 0.3: the last sample still counts.
    let v = lines(&run(&["simulate", "--duration", "0.3", "--every", "0.1"]));
    assert_eq!(v.len(), 1 + 4 + 1);
    let v = lines(&run(&["simulate", "--duration", "1", "--every", "0.3"]));
    assert_eq!(v.len(), 1 + 4 + 1, "0, 0.3, 0.6, 0.9");
}

#[test]
fn numbers_keep_full_precision() {
    let v = lines(&run(&[
        "simulate",
        "--duration",
        "0",
        "--every",
        "1",
        "--angle",
        "30",
    ]));
    let theta0 = v[1]["theta"][0].as_f64().expect("number");
    assert_eq!(theta0, -30f64.to_radians(), "round-trips to the same f64");
}

#[test]
fn asset_choice_is_logged_and_the_built_in_one_works_anywhere() {
    let o = run(&["simulate", "--duration", "0"]);
    assert!(
        stderr(&o).contains("config: assets/cradle.ron"),
        "{}",
        stderr(&o)
    );
    let dir = temp_dir("anywhere");
    let o = run_in(&dir, &["simulate", "--duration", "0"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(stderr(&o).contains("built-in"), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_window_without_a_display_says_so_and_points_to_render() {
    let o = Command::new(env!("CARGO_BIN_EXE_newtons-cradle"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .expect("the binary runs");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("cannot open a window") && err.contains("newtons-cradle render --out"),
        "{err}"
    );
    assert!(!err.contains("panicked") && !err.contains(".rs:"), "{err}");
}

/// Width and height from a PNG's header (IHDR follows the 8-byte signature).
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).expect("png written");
    assert_eq!(
        &bytes[..8],
        b"\x89PNG\r\n\x1a\n",
        "{} is a PNG",
        path.display()
    );
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().expect("4 bytes"));
    (be(16), be(20))
}

#[test]
fn render_writes_a_png_a_sequence_and_a_gif_creating_folders() {
    let dir = temp_dir("render");
    let small = ["--width", "64", "--height", "32"];
    let png = dir.join("deep/er/one.png");
    let o = run(&[
        &[
            "render",
            "--out",
            png.to_str().expect("utf-8"),
            "--time",
            "0.5",
        ][..],
        &small,
    ]
    .concat());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(png_size(&png), (64, 32));

    let seq = dir.join("seq");
    let o = run(&[
        &[
            "render",
            "--frames",
            "3",
            "--fps",
            "10",
            "--out",
            seq.to_str().expect("utf-8"),
        ][..],
        &small,
    ]
    .concat());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    for n in 0..3 {
        assert_eq!(png_size(&seq.join(format!("frame_{n:04}.png"))), (64, 32));
    }
    assert!(!seq.join("frame_0003.png").exists());

    let gif = dir.join("anim.gif");
    let o = run(&[
        &[
            "render",
            "--gif",
            gif.to_str().expect("utf-8"),
            "--frames",
            "4",
        ][..],
        &small,
    ]
    .concat());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let bytes = std::fs::read(&gif).expect("gif written");
    assert_eq!(&bytes[..6], b"GIF89a");
    assert_eq!(u16::from_le_bytes([bytes[6], bytes[7]]), 64);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn render_refuses_unwritable_paths_and_missing_outputs_with_exit_2() {
    let dir = temp_dir("unwritable");
    let blocker = dir.join("a-file");
    std::fs::write(&blocker, b"not a folder").expect("write");
    let inside = blocker.join("x.png");
    let o = run(&[
        "render",
        "--width",
        "32",
        "--height",
        "16",
        "--out",
        inside.to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("cannot write") && stderr(&o).contains("x.png"),
        "{}",
        stderr(&o)
    );
    let o = run(&["render"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--out FILE.png"), "{}", stderr(&o));
    let o = run(&["render", "--out", "x.png", "--fps", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--fps 0: not allowed"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn simulate_runs_hertz_contact() {
    let o = run(&[
        "simulate",
        "--contact",
        "hertz",
        "--duration",
        "1",
        "--every",
        "0.5",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = lines(&o);
    assert_eq!(v[0]["params"]["contact"], "hertz");
    let summary = &v.last().unwrap()["summary"];
    assert!(summary["collisions"].as_u64().is_some_and(|c| c > 0));
    // Every Hertz contact keeps energy to ~1e-12 (tests/hertz.rs).
    assert!(
        summary["max_energy_rel_error"]
            .as_f64()
            .is_some_and(|e| e < 1e-9)
    );
}

#[test]
fn samples_and_aa_flags_set_the_anti_aliasing_and_check_their_range() {
    let dir = temp_dir("aa-flags");
    let render = |name: &str, extra: &[&str]| {
        let png = dir.join(format!("{name}.png"));
        let mut args = vec![
            "render",
            "--width",
            "64",
            "--height",
            "32",
            "--time",
            "0.3",
            "--out",
            png.to_str().expect("utf-8"),
        ];
        args.extend_from_slice(extra);
        let o = run(&args);
        assert_eq!(o.status.code(), Some(0), "{extra:?}: {}", stderr(&o));
        std::fs::read(&png).expect("written")
    };
    let default = render("default", &[]);
    let plain = render("plain", &["--samples", "1"]);
    // One sample is no anti-aliasing, whichever scheme.
    assert_eq!(render("one", &["--samples", "1", "--aa", "uniform"]), plain);
    let uniform = render("uniform", &["--samples", "4", "--aa", "uniform"]);
    let adaptive = render("adaptive", &["--samples", "4", "--aa", "adaptive"]);
    assert_eq!(default, adaptive, "the default: 4 samples at edges");
    assert_ne!(uniform, plain, "4 samples everywhere change the picture");
    assert_ne!(adaptive, plain, "4 samples at edges change the picture");
    assert_ne!(adaptive, uniform, "only the edges are supersampled");
    for (flags, want) in [
        (
            &["--samples", "0"][..],
            "--samples 0: not allowed; allowed: 1..=64",
        ),
        (
            &["--samples", "65"][..],
            "--samples 65: not allowed; allowed: 1..=64",
        ),
        (&["--samples", "2.5"][..], "--samples"),
        (&["--aa", "sideways"][..], "uniform"),
    ] {
        let out = dir.join("refused.png");
        let mut args = vec!["render", "--out", out.to_str().expect("utf-8")];
        args.extend_from_slice(flags);
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{flags:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(want), "{flags:?}: {}", stderr(&o));
        assert!(!out.exists(), "nothing written for a refused flag");
    }
}
