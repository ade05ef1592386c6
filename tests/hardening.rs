//! Hostile input, against the contract: bad input exits 2 with where and what is
//! allowed, other failures exit 1, nothing hangs, and no file is half-written or
//! wrongly replaced.

mod common;

use common::{run, run_in, stderr, temp_dir};
use newtons_cradle::config::{ConfigError, load_file, parse};
use newtons_cradle::export::{Delays, GifWriter, write_png};
use newtons_cradle::trace::Image;
use std::path::Path;
use std::process::{Command, Stdio};

/// Files in `dir` whose names mark an unfinished write.
fn leftovers(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|d| {
            d.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| Path::new(n).extension().is_some_and(|e| e == "part"))
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn configs_that_are_not_regular_files_are_refused_without_reading() {
    let dir = temp_dir("not-files");
    let fifo = dir.join("pipe.ron");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    // A FIFO with no writer would block a read for ever: refused from its metadata.
    for path in [fifo.as_path(), Path::new("/dev/zero"), dir.as_path()] {
        let e = load_file(path).expect_err("not a regular file");
        assert!(matches!(e, ConfigError::NotAFile { .. }), "{path:?}: {e}");
        assert!(e.to_string().contains("allowed: a RON file"), "{e}");
    }
    let big = dir.join("big.ron");
    std::fs::write(&big, vec![b' '; (1 << 20) + 1]).expect("write");
    let e = load_file(&big).expect_err("too large");
    assert!(e.to_string().contains("larger than 1 MiB"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_byte_order_mark_is_accepted_and_bad_numbers_name_their_field() {
    let c = parse("\u{feff}(cradle: (balls: 3))", "bom.ron").expect("a BOM is fine");
    assert_eq!(c.cradle.balls, 3);
    for (src, want) in [
        ("(cradle: (balls: 2.5))", ["`cradle.balls`", "1..=200"]),
        ("(cradle: (balls: -3))", ["`cradle.balls`", "1..=200"]),
        ("(render: (width: 1e3))", ["`render.width`", "16..=8192"]),
        (
            "(render: (samples: 99999999999999999999))",
            ["`render.samples`", "1..=64"],
        ),
        ("(cradle: (radius: abc))", ["`radius`", "t.ron:1:"]),
    ] {
        let e = parse(src, "t.ron").expect_err(src).to_string();
        assert!(want.iter().all(|w| e.contains(w)), "{src}: {e}");
    }
    // An error after a value is not blamed on that value's field.
    let e = parse("(cradle: (balls: 3) (x))", "t.ron")
        .expect_err("syntax")
        .to_string();
    assert!(!e.contains("cradle.balls"), "{e}");
}

#[test]
fn flags_that_are_not_numbers_say_what_is_allowed() {
    for (flag, value, want) in [
        ("--balls", "2.5", "1..=200"),
        ("--balls", "abc", "1..=200"),
        ("--angle", "x", "0..=179.999"),
        ("--gap", "1e400", "0..=10"),
        ("--width", "12.0", "16..=8192"),
    ] {
        let o = run(&["simulate", "--duration", "0", flag, value]);
        assert_eq!(o.status.code(), Some(2), "{flag} {value}");
        let e = stderr(&o);
        assert!(e.contains(flag) && e.contains(want), "{flag} {value}: {e}");
    }
    // A huge number is echoed short, not as 301 digits.
    let o = run(&["simulate", "--duration", "1e300"]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("--duration 1e300: not allowed"), "{e}");
    assert!(e.lines().all(|l| l.len() < 200), "{e}");
}

#[test]
fn every_frame_of_a_sequence_is_capped_not_just_the_first() {
    let dir = temp_dir("last-frame");
    let out = dir.join("seq");
    let o = run(&[
        "render",
        "--time",
        "999999",
        "--frames",
        "100",
        "--fps",
        "1",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("every frame at most 1e6 s"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists(), "nothing traced or written");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn outputs_never_replace_the_input_or_a_file_that_is_not_a_picture_of_ours() {
    let dir = temp_dir("no-replace");
    let small = ["--width", "32", "--height", "16"];
    let render = |args: &[&str]| {
        let mut all = vec!["render"];
        all.extend_from_slice(args);
        all.extend_from_slice(&small);
        run_in(&dir, &all)
    };
    // A config named like a picture, given as both input and output.
    std::fs::write(dir.join("conf.png"), "(cradle: (balls: 3))").expect("write");
    let o = render(&["--config", "conf.png", "--out", "conf.png"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("the config being read"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("conf.png")).expect("read"),
        "(cradle: (balls: 3))"
    );
    // A file that is not a PNG is kept; an extension we do not write is refused.
    std::fs::write(dir.join("notes.png"), "my notes").expect("write");
    let o = render(&["--out", "notes.png"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("refusing to replace"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(dir.join("notes.png")).expect("read"),
        "my notes"
    );
    for (flag, name, ext) in [("--out", "x.jpg", ".png"), ("--gif", "x.mp4", ".gif")] {
        let o = render(&[flag, name]);
        assert_eq!(o.status.code(), Some(2), "{name}");
        assert!(stderr(&o).contains(ext), "{name}: {}", stderr(&o));
        assert!(!dir.join(name).exists());
    }
    // A picture of ours is replaced.
    for _ in 0..2 {
        assert_eq!(render(&["--out", "ok.png"]).status.code(), Some(0));
    }
    assert!(
        std::fs::read(dir.join("ok.png"))
            .expect("read")
            .starts_with(b"\x89PNG")
    );
    // A folder that is a file: said plainly, before tracing.
    let o = render(&["--out", "conf.png/x.png"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("is a file, not a folder"),
        "{}",
        stderr(&o)
    );
    assert!(leftovers(&dir).is_empty());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn output_lost_to_a_full_device_exits_1() {
    for args in [
        &["simulate", "--duration", "1"][..],
        &[
            "bench",
            "render",
            "--json",
            "--frames",
            "1",
            "--threads",
            "1",
            "--width",
            "16",
            "--height",
            "16",
        ][..],
        &["bench", "stress", "--json", "--scale", "0.01"][..],
    ] {
        let full = std::fs::File::create("/dev/full").expect("/dev/full");
        let o = Command::new(env!("CARGO_BIN_EXE_newtons-cradle"))
            .args(args)
            .stdout(full)
            .stderr(Stdio::piped())
            .output()
            .expect("runs");
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("No space left"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
}

#[test]
fn pictures_appear_whole_or_not_at_all() {
    let dir = temp_dir("atomic");
    let img = Image {
        width: 4,
        height: 2,
        rgba: vec![200; 32],
    };
    let png = dir.join("a/b/p.png");
    write_png(&png, &img).expect("written");
    assert!(std::fs::read(&png).expect("read").starts_with(b"\x89PNG"));
    // An unfinished GIF leaves nothing; a finished one ends with its trailer.
    let gif = dir.join("g.gif");
    let mut w = GifWriter::create(&gif, 4, 2, 30.0).expect("created");
    w.push(img.clone()).expect("frame");
    drop(w);
    assert!(
        !gif.exists() && leftovers(&dir).is_empty(),
        "dropped unfinished"
    );
    let mut w = GifWriter::create(&gif, 4, 2, 30.0).expect("created");
    w.push(img.clone()).expect("frame");
    w.finish().expect("finished");
    let bytes = std::fs::read(&gif).expect("read");
    assert!(bytes.starts_with(b"GIF89a") && bytes.ends_with(&[0x3b]));
    assert!(leftovers(&dir).is_empty());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn gif_delays_keep_the_average_rate() {
    // 30 fps in centiseconds: 3.33 each; rounded one by one they would play at
    // 33.3 fps. Spread, 30 frames last exactly 100 cs.
    let mut d = Delays::new(30.0);
    let delays: Vec<u16> = (0..30).map(|_| d.next_delay()).collect();
    assert_eq!(delays.iter().map(|&c| u32::from(c)).sum::<u32>(), 100);
    assert!(delays.iter().all(|&c| c == 3 || c == 4), "{delays:?}");
    let mut d = Delays::new(1000.0);
    assert!((0..10).all(|_| d.next_delay() >= 1), "at least 1 cs each");
}

#[test]
fn ctrl_c_sigterm_and_sighup_leave_no_partial_file() {
    for signal in ["-INT", "-TERM", "-HUP"] {
        interrupted_gif_leaves_nothing(signal);
    }
}

/// A long GIF render stopped by `signal` exits 130 and leaves no file.
fn interrupted_gif_leaves_nothing(signal: &str) {
    let dir = temp_dir(&format!("signal{signal}"));
    let gif = dir.join("long.gif");
    let mut child = Command::new(env!("CARGO_BIN_EXE_newtons-cradle"))
        .args([
            "render",
            "--gif",
            gif.to_str().expect("utf-8"),
            "--frames",
            "2000",
        ])
        .args(["--width", "400", "--height", "200"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("starts");
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let killed = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(killed.success());
    let status = child.wait().expect("ends");
    assert_eq!(status.code(), Some(130), "{signal}: interrupted");
    assert!(!gif.exists(), "{signal}: no GIF without its end");
    assert!(
        leftovers(&dir).is_empty(),
        "{signal}: {:?}",
        leftovers(&dir)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn every_frame_path_of_a_sequence_is_checked_before_tracing() {
    // A file that is not a picture at the last frame's name: refused at once,
    // before a single frame is traced or written.
    let dir = temp_dir("sequence-paths");
    let frames = dir.join("frames");
    std::fs::create_dir_all(&frames).expect("folder");
    std::fs::write(frames.join("frame_0009.png"), "my notes").expect("write");
    let o = run(&[
        "render",
        "--frames",
        "10",
        "--out",
        frames.to_str().expect("utf-8"),
        "--width",
        "32",
        "--height",
        "16",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("frame_0009.png"), "{}", stderr(&o));
    assert!(
        !frames.join("frame_0000.png").exists(),
        "nothing traced first"
    );
    assert_eq!(
        std::fs::read_to_string(frames.join("frame_0009.png")).expect("kept"),
        "my notes"
    );
    // A sequence into a name like a picture's is refused, not made a folder.
    let k = dir.join("k.png");
    let o = run(&[
        "render",
        "--frames",
        "2",
        "--out",
        k.to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("allowed: --out DIR/"), "{}", stderr(&o));
    assert!(!k.exists(), "no folder named k.png");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn messages_name_the_flag_or_key_that_breaks_the_rule() {
    // The asset's dissipation is refused with the RK4 flag: the flag is named.
    let o = run(&[
        "simulate",
        "--config",
        "assets/presets/realistic.ron",
        "--integrator",
        "rk4",
        "--width",
        "100",
        "--duration",
        "0",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(err.contains("refused with --integrator rk4"), "{err}");
    assert!(
        !err.contains("--width") && !err.contains("applying )"),
        "{err}"
    );
    // A sequence whose last frame is too late: no --time that was not given.
    let o = run(&[
        "render", "--frames", "2", "--first", "10000000", "--fps", "1", "--out", "x/",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        !err.contains("--time") && err.contains("frame 10000001"),
        "{err}"
    );
    // A name written as a string: the names allowed.
    let dir = temp_dir("named-values");
    let path = dir.join("quoted.ron");
    std::fs::write(&path, "(contact: (model: \"hertz\"))").expect("write");
    let o = run(&[
        "simulate",
        "--config",
        path.to_str().expect("utf-8"),
        "--duration",
        "0",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("allowed: ideal, hertz"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).ok();
}
