//! `render --audio FILE.wav`: the soundtrack of a sequence or GIF, read back
//! and checked against the impacts `simulate --impacts` prints.

mod common;

use common::{lines, run, stderr, temp_dir};
use std::path::Path;

/// The soundtrack's format, and its samples (left, right interleaved).
fn read(path: &Path) -> (hound::WavSpec, Vec<i16>) {
    let mut r = hound::WavReader::open(path).expect("a WAV file");
    let spec = r.spec();
    let samples = r.samples::<i16>().map(|s| s.expect("a sample")).collect();
    (spec, samples)
}

/// Sample frames where a click starts: the first non-zero frame after at
/// least 50 ms of exact silence. A click's sound ends exactly (at its ring's
/// sixth time constant, 0.18 s), and impacts here are 0.41 s apart; within a
/// click the ring's zero crossings can round to 0 for a frame or two.
fn onsets(samples: &[i16]) -> Vec<usize> {
    let frames: Vec<i32> = samples
        .chunks(2)
        .map(|f| i32::from(f[0]).abs().max(i32::from(f[1]).abs()))
        .collect();
    let mut quiet = usize::MAX / 2;
    let mut found = Vec::new();
    for (i, f) in frames.iter().enumerate() {
        if *f == 0 {
            quiet += 1;
            continue;
        }
        if quiet >= 2400 {
            found.push(i);
        }
        quiet = 0;
    }
    found
}

/// The distinct impact times `simulate --impacts` prints up to `until` (s):
/// each ideal impact of a chain comes at one instant.
fn impact_times(angle: &str, until: f64) -> Vec<f64> {
    let o = run(&[
        "simulate",
        "--duration",
        &until.to_string(),
        "--every",
        "0.1",
        "--impacts",
        "--angle",
        angle,
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let mut times: Vec<f64> = lines(&o)
        .iter()
        .filter_map(|l| l.get("impact"))
        .map(|i| i["t"].as_f64().expect("a time"))
        .filter(|t| *t < until)
        .collect();
    times.dedup();
    times
}

#[test]
fn a_gif_soundtrack_lasts_frames_over_fps_with_each_click_on_its_impact_to_a_sample() {
    let dir = temp_dir("soundtrack");
    let wav = dir.join("swing.wav");
    let gif = dir.join("swing.gif");
    let o = run(&[
        "render",
        "--gif",
        gif.to_str().unwrap(),
        "--frames",
        "45",
        "--fps",
        "30",
        "--width",
        "32",
        "--height",
        "16",
        "--audio",
        wav.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (spec, samples) = read(&wav);
    assert_eq!(
        (spec.sample_rate, spec.channels, spec.bits_per_sample),
        (48_000, 2, 16)
    );
    // 45 frames at 30 fps: exactly 1.5 s.
    assert_eq!(samples.len(), 2 * 72_000);
    let want = impact_times("30", 1.5);
    assert_eq!(want.len(), 4, "{want:?}");
    let got = onsets(&samples);
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (n, t) in got.iter().zip(&want) {
        // The first sample at or after the impact: within one sample (21 us).
        let late = *n as f64 / 48_000.0 - t;
        assert!((0.0..1.0 / 48_000.0).contains(&late), "{n} vs {t}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_later_part_of_a_sequence_has_the_soundtrack_of_its_own_frames() {
    let dir = temp_dir("soundtrack-part");
    let wav = dir.join("part.wav");
    let out = format!("{}/", dir.join("frames").display());
    let o = run(&[
        "render",
        "--frames",
        "10",
        "--first",
        "5",
        "--fps",
        "10",
        "--width",
        "16",
        "--height",
        "16",
        "--out",
        &out,
        "--audio",
        wav.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (_, samples) = read(&wav);
    // Frames 5..=14 at 10 fps: from 0.5 s, for 1 s.
    assert_eq!(samples.len(), 2 * 48_000);
    let want: Vec<f64> = impact_times("30", 1.5)
        .into_iter()
        .filter(|t| *t >= 0.5)
        .collect();
    let got = onsets(&samples);
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (n, t) in got.iter().zip(&want) {
        let late = *n as f64 / 48_000.0 - (t - 0.5);
        assert!((0.0..1.0 / 48_000.0 + 1e-12).contains(&late), "{n} vs {t}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_higher_lift_gives_louder_clicks() {
    let dir = temp_dir("soundtrack-loud");
    let peak = |angle: &str| {
        let wav = dir.join(format!("lift{angle}.wav"));
        let gif = dir.join(format!("lift{angle}.gif"));
        let o = run(&[
            "render",
            "--gif",
            gif.to_str().unwrap(),
            "--frames",
            "30",
            "--width",
            "16",
            "--height",
            "16",
            "--angle",
            angle,
            "--audio",
            wav.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let (_, samples) = read(&wav);
        samples.iter().map(|s| i32::from(*s).abs()).max().unwrap()
    };
    let (low, high) = (peak("10"), peak("45"));
    assert!(low > 0 && high > low + low / 2, "{low} then {high}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_soundtrack_replaces_neither_a_file_of_the_user_nor_a_picture_alone() {
    let dir = temp_dir("soundtrack-refuse");
    let gif = dir.join("a.gif");
    let gif = gif.to_str().unwrap();
    // One picture has no soundtrack.
    let png = dir.join("one.png");
    let o = run(&[
        "render",
        "--out",
        png.to_str().unwrap(),
        "--audio",
        dir.join("a.wav").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--audio"), "{}", stderr(&o));
    // Not a .wav name; a file there that is not a WAV: refused, left as it was.
    let notes = dir.join("notes.wav");
    std::fs::write(&notes, "my notes").unwrap();
    for path in [dir.join("a.txt"), notes.clone()] {
        let o = run(&[
            "render",
            "--gif",
            gif,
            "--frames",
            "2",
            "--audio",
            path.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains(".wav"), "{}", stderr(&o));
    }
    assert_eq!(std::fs::read_to_string(&notes).unwrap(), "my notes");
    assert!(!Path::new(gif).exists(), "nothing rendered");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_soundtrack_that_cannot_be_written_is_a_failure_of_the_run() {
    use newtons_cradle::config::Config;
    use newtons_cradle::headless::{Output, is_bad_path, render};
    let dir = temp_dir("soundtrack-fail");
    std::fs::write(dir.join("file"), "").unwrap();
    let mut config = Config::default();
    config.render.width = 16;
    config.render.height = 16;
    let output = Output::Gif {
        path: dir.join("a.gif"),
        frames: 2,
        fps: 30.0,
    };
    // Its folder became a file while the frames rendered: exit 1, not 2.
    let audio = dir.join("file").join("a.wav");
    let e = render(&config, 0.0, &output, Some(&audio), None).expect_err("cannot write");
    assert!(!is_bad_path(&e), "{e}");
    assert!(e.to_string().contains("a.wav"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}
