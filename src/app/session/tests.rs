//! The session's rules, without a window: keys, respawns, reload, the clock.

use super::{Effect, Session};
use crate::app::keys::Action;
use crate::cli::Common;
use crate::config::{Config, ConfigSource, MAX_BALLS};
use std::time::{Duration, Instant};

/// A small, fast session: 32x16 pixels on one thread.
fn session_with(source: ConfigSource) -> Session {
    let mut config = Config::default();
    config.render.width = 32;
    config.render.height = 16;
    config.render.threads = 1;
    let overrides = Common {
        width: Some(32),
        height: Some(16),
        threads: Some(1),
        ..Common::default()
    };
    Session::new(config, source, overrides).expect("one thread starts")
}

fn session() -> Session {
    session_with(ConfigSource::Builtin)
}

/// A config file holding `text` in a fresh folder named for `test`; returns the
/// folder (to remove) and the file.
fn asset(test: &str, text: &str) -> (std::path::PathBuf, std::path::PathBuf) {
    let dir = std::env::temp_dir().join(format!("nc-session-{test}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("cradle.ron");
    std::fs::write(&path, text).expect("write");
    (dir, path)
}

/// Steps `n` frames of 1/60 s each from `start`.
fn frames(s: &mut Session, start: Instant, n: u32) -> Instant {
    let mut now = start;
    for _ in 0..n {
        now += Duration::from_secs_f64(1.0 / 60.0);
        s.step(now);
    }
    now
}

#[test]
fn starts_paused_and_space_runs_the_clock() {
    let mut s = session();
    let now = Instant::now();
    s.step(now);
    assert!(!s.running(), "the default asset starts paused");
    let now = frames(&mut s, now, 10);
    assert_eq!(s.time(), 0.0, "paused: the clock stands still");
    assert_eq!(s.act(Action::TogglePause), Effect::Redraw);
    assert!(s.running());
    s.step(now);
    frames(&mut s, now, 30);
    // 30 frames of 1/60 s after the first: half a second. `Duration` keeps whole
    // nanoseconds, so each frame is 1/3 ns long: 1e-8 s over 30, within 1e-7.
    assert!((s.time() - 0.5).abs() < 1e-7, "t = {}", s.time());
}

#[test]
fn quick_arrow_presses_keep_the_swing_running() {
    let mut s = session();
    s.act(Action::TogglePause);
    let now = frames(&mut s, Instant::now(), 5);
    // Two respawns before any frame runs: the second must not read a stale state.
    for a in [Action::Balls(1), Action::Lift(1), Action::Balls(-1)] {
        s.act(a);
        assert!(s.running(), "{a:?} stopped the swing");
    }
    frames(&mut s, now, 5);
    assert!(s.running());
    assert!(s.time() > 0.0, "the respawned swing runs");
}

#[test]
fn counts_stay_in_range_and_reset_restores_the_asset() {
    let mut s = session();
    let asset = s.config().clone();
    for _ in 0..=asset.start.lift {
        s.act(Action::Lift(-1));
    }
    assert_eq!(s.config().start.lift, 0, "no fewer than none lifted");
    for _ in 0..asset.cradle.balls + 3 {
        s.act(Action::Lift(1));
    }
    assert_eq!(
        s.config().start.lift,
        asset.cradle.balls,
        "at most every ball"
    );
    for _ in 0..asset.cradle.balls + 3 {
        s.act(Action::Balls(-1));
    }
    assert_eq!(s.config().cradle.balls, 1, "at least one ball");
    assert_eq!(
        s.config().start.lift,
        1,
        "lifted follows the ball count down"
    );
    for _ in 0..MAX_BALLS + 3 {
        s.act(Action::Balls(1));
    }
    assert_eq!(s.config().cradle.balls, MAX_BALLS);
    s.act(Action::TogglePause);
    s.act(Action::Reset);
    assert_eq!(s.config(), &asset);
    assert!(!s.running(), "reset restores the asset's run state");
}

#[test]
fn a_drag_from_the_left_becomes_the_lifted_count_and_angle() {
    use crate::scene::layout::Layout;
    use crate::trace::camera::CameraRays;
    use glam::DVec3;
    let mut s = session();
    s.step(Instant::now());
    let c = s.config().clone();
    let rays = CameraRays::new(&s.world.scene().camera, c.render.width, c.render.height);
    let layout = Layout::new(&c);
    // Ball 3 (the middle one, at rest) pulled out to the left lifts balls 1..=3.
    let centre = layout.pivot(2) + DVec3::new(0.0, -c.cradle.length, 0.0);
    let (x, y) = rays.project(centre.as_vec3()).expect("in view");
    assert!(s.grab((f64::from(x), f64::from(y))));
    let target = layout.pivot(2) + DVec3::new(-0.1, -0.1, 0.0);
    let (x, y) = rays.project(target.as_vec3()).expect("in view");
    assert!(s.drag_to((f64::from(x), f64::from(y))));
    let theta = s.world.cradle().snapshot.theta.clone();
    assert_eq!(s.config().start.lift, 3);
    // The angle of the pulled balls, to the degree shown (the pixel's ray is f32).
    assert!(
        (s.config().start.angle_deg - 45.0).abs() < 0.5,
        "{}",
        s.config().start.angle_deg
    );
    assert_eq!(s.config().start.angle_deg, theta[2].abs().to_degrees());
    let hud = s.hud_lines();
    assert!(
        hud[1].0.contains(&format!(
            "lifted 3 at {:.1} deg",
            s.config().start.angle_deg
        )),
        "{hud:?}"
    );
    assert_eq!(s.controls().lift, 3, "the panel shows it too");
    s.release();
    assert!(s.running());
}

#[test]
fn reset_goes_back_to_the_normal_time_rate_and_says_so() {
    let mut s = session();
    s.act(Action::Rate(1));
    s.act(Action::Rate(1));
    assert_eq!(s.rate(), 4.0);
    s.act(Action::Reset);
    assert_eq!(s.rate(), 1.0);
    let notices = s.overlay(Instant::now()).notices;
    assert!(
        notices.iter().any(|(t, _)| t.contains("reset")),
        "{notices:?}"
    );
}

#[test]
fn presets_load_in_place_and_ctrl_z_undoes_panel_changes() {
    let mut s = session();
    let start = s.config().clone();
    let realistic = crate::app::presets::PRESETS
        .iter()
        .position(|p| p.name == "realistic")
        .expect("listed");
    s.load_preset(realistic);
    assert!(s.config().cradle_params().dissipative());
    assert_eq!(
        (s.config().render.width, s.config().render.height),
        (32, 16),
        "the window's size stays"
    );
    let notices = s.overlay(Instant::now()).notices;
    assert!(
        notices.iter().any(|(t, _)| t == "preset loaded: realistic"),
        "{notices:?}"
    );
    // R now returns to the preset's start.
    s.act(Action::Reset);
    assert!(s.config().cradle_params().dissipative());
    s.act(Action::Undo);
    assert_eq!(s.config(), &start, "undo: the cradle before the preset");
    // A panel edit, undone; then nothing left to undo.
    let mut c = s.controls();
    c.balls = 9;
    s.apply_controls(&c);
    assert_eq!(s.config().cradle.balls, 9);
    s.act(Action::Undo);
    assert_eq!(s.config(), &start);
    s.act(Action::Undo);
    assert_eq!(s.config(), &start);
    let notices = s.overlay(Instant::now()).notices;
    assert!(
        notices.iter().any(|(t, _)| t == "nothing to undo"),
        "{notices:?}"
    );
}

#[test]
fn a_refused_panel_value_shows_a_notice_and_changes_nothing() {
    let mut s = session();
    let before = s.config().clone();
    let mut c = s.controls();
    c.contact = crate::config::ContactModel::Hertz;
    c.restitution = 0.5;
    s.apply_controls(&c);
    assert_eq!(s.config(), &before);
    let notices = s.overlay(Instant::now()).notices;
    assert!(
        notices
            .iter()
            .any(|(t, _)| t.starts_with("not applied:") && t.contains("contact.restitution")),
        "{notices:?}"
    );
}

#[test]
fn window_actions_are_left_to_the_window() {
    let mut s = session();
    assert_eq!(s.act(Action::Screenshot), Effect::Screenshot);
    assert_eq!(s.act(Action::Replay), Effect::Replay);
    assert_eq!(s.act(Action::Quit), Effect::Quit);
}

#[test]
fn hud_cycles_status_help_and_off_but_errors_stay() {
    let mut s = session();
    s.step(Instant::now());
    let status = s.hud_lines();
    assert!(status[0].0.contains("PAUSED"), "{:?}", status[0]);
    assert!(!s.overlay(Instant::now()).help);
    s.act(Action::ToggleHud);
    assert!(s.overlay(Instant::now()).help, "help adds the key list");
    assert!(!s.hud_lines().is_empty(), "with the status");
    s.act(Action::ToggleHud);
    assert!(s.hud_lines().is_empty(), "off shows nothing");
    assert!(!s.overlay(Instant::now()).help);
    s.error = Some("line 3".into());
    assert_eq!(
        s.hud_lines().len(),
        1,
        "an error shows even with the HUD off"
    );
}

#[test]
fn a_bad_reload_keeps_the_scene_and_shows_where() {
    let (dir, path) = asset("reload", "(cradle: (balls: 7))");
    let mut s = session_with(ConfigSource::File(path.clone()));
    s.reload(|_, _| Ok(()));
    assert_eq!(s.config().cradle.balls, 7, "a good save applies");
    assert_eq!(s.config().render.width, 32, "with the overrides again");
    std::fs::write(&path, "(cradle: (balls: 0))").expect("write");
    s.reload(|_, _| Ok(()));
    assert_eq!(s.config().cradle.balls, 7, "a bad save keeps the scene");
    let error = s.error().expect("the error is shown").to_owned();
    assert!(
        error.contains("cradle.balls") && error.contains("1..=200"),
        "{error}"
    );
    std::fs::write(&path, "(cradle: (balls: 3))").expect("write");
    s.reload(|_, _| Ok(()));
    assert_eq!(s.error(), None, "the next good save clears it");
    assert_eq!(s.config().cradle.balls, 3);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_refused_framebuffer_keeps_the_scene() {
    let (dir, path) = asset("framebuffer", "(cradle: (balls: 4))");
    let mut s = session_with(ConfigSource::File(path.clone()));
    // No overrides for the size here: the asset's 1200x600 differs from 32x16.
    s.overrides = Common::default();
    s.reload(|_, _| Err("no texture".into()));
    assert_eq!(s.config().cradle.balls, 5, "kept");
    assert!(s.error().is_some_and(|e| e.contains("no texture")));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_window_traces_at_most_4k_pixels_keeping_the_shape() {
    let mut config = Config::default();
    (config.render.width, config.render.height) = (8192, 8192);
    crate::app::fit_window(&mut config);
    let (w, h) = (config.render.width, config.render.height);
    assert!(w * h <= crate::app::MAX_WINDOW_PIXELS, "{w}x{h}");
    assert_eq!(w, h, "square stays square");
    assert!(w > 2800, "{w}: no smaller than it must be");
    let mut small = Config::default();
    crate::app::fit_window(&mut small);
    assert_eq!(small, Config::default(), "sizes within the cap are kept");
}

#[test]
fn the_window_caps_samples_and_balls_work_too() {
    let most = crate::app::max_window_work();
    // 4K at 64 uniform samples (once a window that never quit): the samples go
    // first, down to what fits; the size stays.
    let mut c = Config::default();
    (c.render.width, c.render.height) = (3840, 2160);
    (c.render.samples, c.render.adaptive) = (64, false);
    crate::app::fit_window(&mut c);
    assert_eq!((c.render.width, c.render.height), (3840, 2160));
    assert_eq!(c.render.samples, 1, "uniform samples multiply the work");
    // 4K at 200 balls: one sample and still too much: a smaller picture of the
    // same shape, within the cap.
    let mut c = Config::default();
    (c.render.width, c.render.height) = (3840, 2160);
    c.cradle.balls = 200;
    crate::app::fit_window(&mut c);
    assert_eq!(c.render.samples, 1);
    let (w, h) = (c.render.width, c.render.height);
    assert!(
        w < 3840 && (f64::from(w) / f64::from(h) - 16.0 / 9.0).abs() < 0.01,
        "{w}x{h}"
    );
    assert!(crate::app::window_work(&c) <= most * 1.0001);
    // The default window at 200 balls is within the cap: untouched.
    let mut c = Config::default();
    c.cradle.balls = 200;
    let before = c.clone();
    crate::app::fit_window(&mut c);
    assert_eq!(c, before);
}

#[test]
fn time_rates_halve_and_double_within_bounds_and_scale_the_clock() {
    let mut s = session();
    for _ in 0..10 {
        s.act(Action::Rate(-1));
    }
    assert_eq!(s.rate(), 1.0 / 16.0, "no slower than 1/16x");
    for _ in 0..10 {
        s.act(Action::Rate(1));
    }
    assert_eq!(s.rate(), 4.0, "no faster than 4x");
    s.act(Action::Rate(-1));
    s.act(Action::Rate(-1));
    s.act(Action::Rate(-1));
    assert_eq!(s.rate(), 0.5);
    s.act(Action::TogglePause);
    let now = Instant::now();
    s.step(now);
    frames(&mut s, now, 60);
    // 60 frames of 1/60 s at half speed: half a second of simulated time (each
    // frame's Duration is rounded to whole nanoseconds).
    assert!((s.time() - 0.5).abs() < 1e-7, "t = {}", s.time());
}

#[test]
fn n_advances_one_frame_at_the_rate_only_while_paused() {
    let mut s = session();
    s.step(Instant::now());
    s.act(Action::Rate(-1));
    s.act(Action::Step);
    s.act(Action::Step);
    // Two frames of 1/60 s at 1/2x; the physics is queried at that time.
    assert_eq!(s.time(), 2.0 * super::STEP * 0.5);
    s.act(Action::TogglePause);
    let t = s.time();
    s.act(Action::Step);
    assert_eq!(s.time(), t, "while running, the clock is the clock");
}

#[test]
fn dragging_the_right_end_ball_lifts_it_and_letting_go_swings_it() {
    use crate::scene::layout::Layout;
    use crate::trace::camera::CameraRays;
    use glam::DVec3;
    let mut s = session();
    s.step(Instant::now());
    let c = s.config().clone();
    let (w, h) = (c.render.width, c.render.height);
    let cam = s.world.scene().camera;
    let rays = CameraRays::new(&cam, w, h);
    let layout = Layout::new(&c);
    let last = c.cradle.balls - 1;
    let centre = layout.pivot(last) + DVec3::new(0.0, -c.cradle.length, 0.0);
    let (x, y) = rays.project(centre.as_vec3()).expect("in view");
    assert!(
        s.grab((f64::from(x), f64::from(y))),
        "the right-end ball is under the cursor"
    );
    let target = layout.pivot(last) + DVec3::new(0.08, -0.12, 0.0);
    let (x, y) = rays.project(target.as_vec3()).expect("in view");
    assert!(s.drag_to((f64::from(x), f64::from(y))));
    let theta = s.world.cradle().snapshot.theta.clone();
    assert!(theta[last] > 0.3, "lifted to the right: {theta:?}");
    // The asset lifts ball 0: the drag's state replaces it.
    assert!(theta[..last].iter().all(|&t| t == 0.0), "{theta:?}");
    assert!(!s.running(), "held while dragged");
    let hud = s.hud_lines();
    assert!(
        hud[0].0.contains("HOLDING ball 5: let go to swing"),
        "{hud:?}"
    );
    // The HUD says what the drag made, not the asset's "lifted 1 at 30".
    let deg = theta[last].to_degrees();
    assert!(
        hud[1]
            .0
            .contains(&format!("lifted custom (ball 5 at {deg:.1} deg right)")),
        "{hud:?}"
    );
    s.release();
    assert!(s.running(), "let go, it swings");
    let now = frames(&mut s, Instant::now(), 12);
    frames(&mut s, now, 12);
    assert!(
        s.world.cradle().snapshot.theta[last] < theta[last],
        "it swings down"
    );
}

#[test]
fn a_lossy_cradle_shows_the_energy_left_and_the_panel_sets_the_losses() {
    let (dir, path) = asset(
        "lossy",
        "(contact: (model: hertz, dissipation: 5e-7), cradle: (air_density: 1.2))",
    );
    let mut s = session_with(ConfigSource::File(path));
    s.reload(|_, _| Ok(()));
    let now = Instant::now();
    s.step(now);
    s.act(Action::TogglePause);
    s.step(now);
    let full = s.hud_lines()[1].0.clone();
    assert!(full.contains("energy left 100.0%"), "{full}");
    // Two seconds: a few strikes, each losing some percent.
    frames(&mut s, now, 120);
    let (_, (left, error)) = s.energies();
    assert!(left < 0.9 && left > 0.0, "{left}");
    assert!(error.abs() < 1e-8, "the balance holds: {error}");
    let line = s.hud_lines()[1].0.clone();
    assert!(
        line.contains(&format!("energy left {:.1}%", 100.0 * left)),
        "{line}"
    );
    // The panel turns the losses off (elastic again, a restart) and refuses
    // dissipation with ideal impacts, naming the key.
    let mut c = s.controls();
    c.dissipation = 0.0;
    c.air_density = 0.0;
    s.apply_controls(&c);
    assert!(!s.config().cradle_params().dissipative());
    assert!(s.hud_lines()[1].0.contains("energy err"));
    let mut bad = s.controls();
    bad.contact = crate::config::ContactModel::Ideal;
    bad.dissipation = 1e-6;
    s.apply_controls(&bad);
    assert!(s.error().is_some_and(|e| e.contains("contact.dissipation")));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_moving_view_traces_one_sample_per_pixel_until_it_rests() {
    use crate::app::mouse::ViewChange;
    let mut s = session();
    let now = Instant::now();
    s.step(now);
    let aa = s.config().render.samples;
    assert!(aa > 1, "the default anti-aliases");
    assert_eq!(s.world.scene().samples, aa);
    s.view(ViewChange::Turn(5.0, 0.0));
    s.step(now);
    assert_eq!(s.world.scene().samples, 1, "a moving view: one sample");
    let rest = s.settle().expect("the window wakes when it rests");
    s.step(now + Duration::from_millis(100));
    assert_eq!(s.world.scene().samples, 1, "not rested yet");
    s.step(rest);
    assert_eq!(s.world.scene().samples, aa, "rested: anti-aliased again");
    let threshold = s.config().render.adaptive_threshold as f32;
    assert_eq!(
        s.world.scene().adaptive,
        Some(threshold),
        "at the config's threshold"
    );
    assert_eq!(s.settle(), None);
}

#[test]
fn pipelined_frames_show_the_frame_before_and_a_pause_shows_the_last_state() {
    // Two sessions stepped alike: one traces in line, one pipelined (as the
    // window does: step, show, launch).
    let (mut inline, mut piped) = (session(), session());
    piped.pipeline();
    let start = Instant::now();
    for s in [&mut inline, &mut piped] {
        s.step(start);
        s.act(Action::TogglePause);
    }
    let mut shown = Vec::new();
    let mut now = start;
    for _ in 0..6 {
        now += Duration::from_secs_f64(1.0 / 30.0);
        inline.step(now);
        piped.step(now);
        let want = inline.image().expect("traced in line").rgba.clone();
        let got = piped.image().map(|i| i.rgba.clone());
        piped.launch();
        shown.push((want, got));
    }
    // Each pipelined step shows what the in-line session showed a step before.
    for k in 1..shown.len() {
        let got = shown[k].1.as_ref().expect("a frame came back");
        assert!(*got == shown[k - 1].0, "step {k}: the frame before");
    }
    assert!(
        shown.windows(2).any(|w| w[0].0 != w[1].0),
        "the swing moves, so frames differ"
    );
    // Paused, the next step takes the last frame back and shows the state the
    // clock stopped at, as the in-line session does.
    for s in [&mut inline, &mut piped] {
        s.act(Action::TogglePause);
        s.step(now);
    }
    piped.launch();
    assert!(inline.image().expect("in line").rgba == piped.image().expect("piped").rgba);
    assert_eq!(inline.time(), piped.time());
}

#[test]
fn impacts_are_heard_once_with_their_frame_and_never_after_a_pause_or_when_muted() {
    let mut s = session();
    s.pipeline();
    let now = Instant::now();
    s.step(now);
    s.act(Action::TogglePause);
    // The default cradle's first impact comes at 0.205 s: by 0.25 s (15
    // frames), heard once, each at its simulated time before the frame's.
    let mut heard = Vec::new();
    let mut now = now;
    for _ in 0..15 {
        now = frames(&mut s, now, 1);
        s.launch();
        heard.extend(s.heard());
    }
    let times: Vec<f64> = heard
        .iter()
        .flat_map(|a| a.impacts.impacts.iter().map(move |i| (i.t, a.t)))
        .map(|(t, frame)| {
            assert!(t <= frame, "an impact is heard with a frame at or after it");
            t
        })
        .collect();
    assert_eq!(times.len(), 4, "the chain's four contacts, once: {times:?}");
    // Pipelined, the frame stepped with the next impact is still tracing when
    // the swing is paused: its impacts are dropped, not heard after.
    let hushes = s.hushes();
    for _ in 0..13 {
        now = frames(&mut s, now, 1);
        s.launch();
        assert!(
            s.heard().is_empty() || s.time() > 0.614,
            "no impact before the second"
        );
    }
    s.act(Action::TogglePause);
    assert!(s.hushes() > hushes, "the sound is told to drop what it has");
    frames(&mut s, now, 3);
    assert!(s.heard().is_empty());
    // Muted: nothing is heard, whatever the frames show.
    assert!(!s.muted());
    s.act(Action::Mute);
    assert!(s.muted());
    assert!(s.hud_lines()[1].0.contains("MUTED"));
    s.act(Action::TogglePause);
    for _ in 0..60 {
        now = frames(&mut s, now, 1);
        s.launch();
        assert!(s.heard().is_empty());
    }
}
