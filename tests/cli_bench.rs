//! The `bench` subcommands' contracts: their JSON Lines, tables, plots and flag
//! ranges.

mod common;

use common::{lines, run, stderr, temp_dir};

#[test]
fn bench_render_prints_full_and_incremental_json_lines_per_thread_count() {
    let o = run(&[
        "bench", "render", "--json", "--frames", "2", "--width", "48", "--height", "24",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = lines(&o);
    let cores = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    assert_eq!(
        v.len(),
        2 * cores,
        "a full and an incremental row per thread count"
    );
    for (i, row) in v.iter().enumerate() {
        assert_eq!(row["threads"].as_u64(), Some(i as u64 / 2 + 1));
        assert_eq!(row["mode"], if i % 2 == 0 { "full" } else { "incremental" });
        assert_eq!(
            (row["width"].as_u64(), row["height"].as_u64()),
            (Some(48), Some(24))
        );
        assert_eq!(row["frames"].as_u64(), Some(2));
        assert!(row["ms_median"].as_f64().is_some_and(|ms| ms > 0.0));
    }
}

/// `bench render` of one frame on one thread at 32x16, in JSON, with `extra`.
fn tiny_render(extra: &[&str]) -> std::process::Output {
    let base = [
        "bench",
        "render",
        "--json",
        "--frames",
        "1",
        "--threads",
        "1",
        "--width",
        "32",
        "--height",
        "16",
    ];
    run(&[&base[..], extra].concat())
}

#[test]
fn bench_render_mode_times_one_mode_alone() {
    for (mode, want) in [("full", "full"), ("incremental", "incremental")] {
        let o = tiny_render(&["--mode", mode]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let v = lines(&o);
        assert_eq!(v.len(), 1, "one row for one thread count and one mode");
        assert_eq!(v[0]["mode"], want);
    }
    let o = run(&["bench", "render", "--mode", "fast"]);
    assert_eq!(o.status.code(), Some(2), "an unknown mode is bad input");
    assert!(
        stderr(&o).contains("full"),
        "names the modes: {}",
        stderr(&o)
    );
}

#[test]
fn bench_render_orbit_reports_the_moving_views_psnr_against_the_frame_at_rest() {
    let o = tiny_render(&["--mode", "orbit"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = lines(&o);
    assert_eq!(v.len(), 1, "one row for one thread count");
    assert_eq!(v[0]["mode"], "orbit");
    // A 2x2-block preview of the same view: close to the resting frame (well
    // above the ~10 dB of an unrelated picture) but not equal to it (finite).
    let psnr = v[0]["psnr"].as_f64().expect("orbit rows carry a PSNR");
    assert!((15.0..80.0).contains(&psnr), "PSNR {psnr} dB");
    let o = tiny_render(&["--mode", "full"]);
    assert!(
        lines(&o)[0]["psnr"].is_null(),
        "only orbit rows have a PSNR"
    );
}

#[test]
fn bench_render_without_skips_times_full_frames_and_needs_mode_full() {
    let with = tiny_render;
    let o = with(&["--mode", "full", "--without", "tiles,shadows,bvh,packets"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = lines(&o);
    assert_eq!(v.len(), 1);
    assert_eq!(v[0]["mode"], "full");
    for refused in [
        &["--without", "bvh"][..],
        &["--mode", "both", "--without", "bvh"],
    ] {
        let o = with(refused);
        assert_eq!(o.status.code(), Some(2), "{refused:?}");
        assert!(stderr(&o).contains("--mode full"), "{}", stderr(&o));
    }
    let o = with(&["--mode", "full", "--without", "mirrors"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("packets"),
        "the allowed values: {}",
        stderr(&o)
    );
}

#[test]
fn bench_physics_prints_each_integrator_and_step_and_plots() {
    let dir = temp_dir("bench-physics");
    let svg = dir.join("wp.svg");
    let o = run(&[
        "bench",
        "physics",
        "--json",
        "--duration",
        "2",
        "--min-dt",
        "1e-3",
        "--angle",
        "30",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = lines(&o);
    // exact once, then 4 integrators x 1e-2, 4.6e-3, 2.2e-3, 1e-3.
    assert_eq!(v.len(), 1 + 4 * 4, "{v:?}");
    assert_eq!(v[0]["integrator"], "exact");
    assert!(v[0]["dt"].is_null());
    for row in &v {
        assert!(row["error"].as_f64().is_some_and(|e| e >= 0.0), "{row}");
        assert!(
            row["cpu_seconds"].as_f64().is_some_and(|s| s > 0.0),
            "{row}"
        );
    }
    // Halving the step of rk4 cuts its error: the sweep measures convergence.
    let rk4: Vec<f64> = v
        .iter()
        .filter(|r| r["integrator"] == "rk4")
        .map(|r| r["error"].as_f64().unwrap())
        .collect();
    assert!(rk4.windows(2).all(|w| w[1] < w[0]), "{rk4:?}");
    let text = std::fs::read_to_string(&svg).expect("the plot is written");
    assert!(text.starts_with("<svg") && text.contains("yoshida4"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bench_flags_out_of_range_exit_2() {
    let cases: [(&[&str], &str); 4] = [
        (
            &["bench", "physics", "--duration", "0"],
            "--duration 0: not allowed; allowed: 0.1..=3600",
        ),
        (
            &["bench", "physics", "--min-dt", "1"],
            "--min-dt 1: not allowed; allowed: 1e-7..=1e-2",
        ),
        (
            &["bench", "stress", "--scale", "-1"],
            "--scale -1: not allowed; allowed: 0.01..=1000",
        ),
        (
            &["bench", "render-quality", "--frames", "0"],
            "--frames 0: not allowed; allowed: 1..=1000",
        ),
    ];
    for (args, want) in cases {
        let o = run(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(want), "{args:?}: {}", stderr(&o));
    }
}

#[test]
fn bench_render_quality_rows_per_mode_and_depth() {
    let o = run(&[
        "bench",
        "render-quality",
        "--json",
        "--frames",
        "1",
        "--width",
        "40",
        "--height",
        "20",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = lines(&o);
    assert_eq!(v.len(), 5 * 6, "5 modes x depths 0..=5");
    // The default, adaptive 4, is among them.
    assert!(v.iter().any(|r| r["mode"] == "adaptive 4"));
    for row in &v {
        assert!(row["rmse"].as_f64().is_some_and(|e| e >= 0.0), "{row}");
        assert!(
            row["ms_median"].as_f64().is_some_and(|ms| ms > 0.0),
            "{row}"
        );
    }
    // 16 samples compared with themselves: no error, so no finite PSNR.
    assert!(
        v.iter()
            .filter(|r| r["mode"] == "16 spp")
            .all(|r| r["psnr_vs_16"].is_null())
    );
}

#[test]
fn bench_stress_table_closes_with_the_count_passed_and_keeps_short_times() {
    let o = run(&["bench", "stress", "--scale", "0.01"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    let rows: Vec<&str> = out.lines().collect();
    let last = rows.last().expect("a table");
    // Every row between the header and the closing line is a scenario.
    let scenarios = rows.len() - 3;
    assert_eq!(
        *last,
        format!("stress suite: {scenarios} of {scenarios} scenarios passed")
    );
    // The "sim s" column of a scenario run for 0.1 s or less keeps its
    // decimals instead of rounding to 0.
    let sims: Vec<f64> = rows[2..rows.len() - 1]
        .iter()
        .map(|r| {
            let fields: Vec<&str> = r.split_whitespace().collect();
            // The name may hold spaces; the six numbers end the row.
            fields[fields.len() - 6]
                .parse()
                .expect("a number of seconds")
        })
        .collect();
    assert!(sims.iter().all(|&s| s > 0.0), "{sims:?}");
}
