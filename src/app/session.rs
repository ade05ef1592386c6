//! The window-free session: run state, the user's controls, respawn and reload,
//! the clock between frames, and what the HUD says. The handler feeds it keys and
//! redraws; it steps the ECS world and the incremental tracer. Nothing here knows
//! of winit or pixels, so its rules are unit-tested without a display.

use super::controls::History;
use super::fit_window;
use super::keys::Action;
use super::mouse::ViewChange;
use super::notice::{self, Notices};
use super::orbit::Orbit;
use super::presets::{self, PRESETS};
use crate::cli::{Common, InputError};
use crate::config::{Config, ConfigSource, MAX_BALLS};
use crate::scene::CradleWorld;
use crate::trace::{self, Changes, Image};
use std::time::Instant;

/// Longest simulated step of one frame (s): after a stall the swing continues
/// instead of jumping ahead.
pub const MAX_FRAME_DT: f64 = 0.25;

/// What the HUD shows; H or F1 steps through them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HudMode {
    /// State, timing, energy error, and a hint.
    Status,
    /// The status and the key list.
    Help,
    /// Nothing (errors still show).
    Off,
}

impl HudMode {
    fn next(self) -> Self {
        match self {
            Self::Status => Self::Help,
            Self::Help => Self::Off,
            Self::Off => Self::Status,
        }
    }
}

/// What the window must do after an action the session cannot do itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Effect {
    /// Nothing more than a redraw.
    Redraw,
    /// Save what the window shows.
    Screenshot,
    /// Save what the window showed over the last seconds.
    Replay,
    /// Close the window.
    Quit,
}

/// A line of HUD text and its colour.
pub type HudLine = (String, [u8; 3]);

/// The app's state between frames.
pub struct Session {
    /// The asset as loaded (with the command line's overrides): what R returns to.
    asset: Config,
    /// The asset with the user's changes (ball and lift counts).
    config: Config,
    source: ConfigSource,
    overrides: Common,
    world: CradleWorld,
    pool: rayon::ThreadPool,
    /// Traces frames, re-tracing only what the swing can change; in the
    /// window, running frames trace while the one before is shown.
    tracer: tracer::Tracer,
    /// The scene changed while paused: trace once more.
    retrace: bool,
    last_frame: Option<Instant>,
    /// Smoothed frames per second and trace milliseconds.
    fps: f64,
    trace_ms: f64,
    /// The log's line every 2 s while running.
    rate_log: rate_log::RateLog,
    hud: HudMode,
    error: Option<String>,
    /// Simulated seconds per wall-clock second: a power of two, 1/16..=4.
    rate: f64,
    /// The user's view, as offsets from the asset's camera.
    orbit: Orbit,
    /// The ball being dragged, if one is.
    dragging: Option<usize>,
    /// The control panel is shown.
    panel: bool,
    /// When the view last moved: until it rests for [`VIEW_REST`], frames trace
    /// one sample per pixel, so a drag of the view keeps up.
    view_moved: Option<Instant>,
    /// What the user just did, shown for a moment.
    notices: Notices,
    /// The lifted balls of a drag to the right, which the config's start (balls
    /// lifted from the left) cannot say: "balls 4-5 at 31.0 deg right".
    custom: Option<String>,
    /// The states before the panel's last changes, for Ctrl+Z.
    history: History<(Config, Config, f64)>,
    /// The right edge (a share of the width) of the region the view fits the
    /// cradle into: left of the control panel while it is open.
    fit_right: f32,
    /// The last frame's physics could not reach the clock's time within
    /// [`PHYSICS_BUDGET`]: the swing runs slower than the rate says.
    behind: bool,
    /// Impacts waiting for the frame that shows them, and the mute.
    hearing: Hearing,
}

/// The right edge of the fit region without the panel.
const FULL_WIDTH: f32 = 1.0 - crate::scene::view::FIT_SIDE;

/// The wall-clock time a frame's physics may take: past it, the frame shows
/// the latest state reached, and the swing runs slower than asked.
pub const PHYSICS_BUDGET: std::time::Duration = std::time::Duration::from_millis(50);

/// How long the view must rest before frames are anti-aliased again.
pub const VIEW_REST: std::time::Duration = std::time::Duration::from_millis(250);

/// The time rates `,` and `.` step through: 1/16x ..= 4x, by powers of two.
pub const RATES: std::ops::RangeInclusive<i32> = -4..=2;

/// Simulated time one `N` press advances (s, before the rate): one frame at 60 Hz.
pub const STEP: f64 = 1.0 / 60.0;

impl Session {
    /// A session showing `config`, which came from `source` with `overrides`.
    ///
    /// # Errors
    /// When the tracing threads cannot be started.
    pub fn new(
        mut config: Config,
        source: ConfigSource,
        overrides: Common,
    ) -> anyhow::Result<Self> {
        fit_window(&mut config);
        let muted = overrides.mute;
        Ok(Self {
            pool: trace::pool(config.render.threads)?,
            world: CradleWorld::new(&config),
            asset: config.clone(),
            config,
            source,
            overrides,
            tracer: tracer::Tracer::default(),
            retrace: true,
            last_frame: None,
            fps: 0.0,
            trace_ms: 0.0,
            rate_log: rate_log::RateLog::default(),
            hud: HudMode::Status,
            error: None,
            rate: 1.0,
            orbit: Orbit::default(),
            dragging: None,
            panel: false,
            view_moved: None,
            notices: Notices::default(),
            custom: None,
            history: History::default(),
            fit_right: FULL_WIDTH,
            behind: false,
            hearing: Hearing::new(muted),
        })
    }

    /// Simulated seconds per wall-clock second.
    #[must_use]
    pub fn rate(&self) -> f64 {
        self.rate
    }

    /// The config shown now (the asset with the user's changes).
    #[must_use]
    pub fn config(&self) -> &Config {
        &self.config
    }

    /// Whether the swing runs.
    #[must_use]
    pub fn running(&self) -> bool {
        self.world.state() == crate::scene::SimState::Running
    }

    /// The error shown in the HUD, if any.
    #[must_use]
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// Does what a key asks; says what is left for the window to do.
    pub fn act(&mut self, action: Action) -> Effect {
        match action {
            Action::TogglePause => {
                self.world.set_running(!self.running());
                self.restart_clock();
            }
            Action::Reset => {
                // Back to the asset's start (ball and lift counts, run state) at
                // the normal time rate; the view stays (C resets it).
                self.config = self.asset.clone();
                self.rate = 1.0;
                self.custom = None;
                self.world.respawn(&self.config);
                self.show_view();
                self.restart_clock();
                self.notify("reset: the asset's start, time rate 1x", notice::GOOD);
            }
            Action::Lift(d) => {
                let lift = self.config.start.lift.checked_add_signed(d as isize);
                if let Some(lift) = lift.filter(|&l| l <= self.config.cradle.balls) {
                    self.config.start.lift = lift;
                    self.respawn();
                }
            }
            Action::Balls(d) => {
                let balls = self.config.cradle.balls.checked_add_signed(d as isize);
                if let Some(balls) = balls.filter(|b| (1..=MAX_BALLS).contains(b)) {
                    self.config.cradle.balls = balls;
                    self.config.start.lift = self.config.start.lift.min(balls);
                    self.respawn();
                }
            }
            Action::ToggleHud => self.hud = self.hud.next(),
            Action::Rate(d) => {
                let e = (self.rate.log2().round() as i32 + d).clamp(*RATES.start(), *RATES.end());
                self.rate = 2f64.powi(e);
            }
            Action::Panel => {
                self.panel = !self.panel;
                if !self.panel {
                    self.set_panel_edge(None);
                }
            }
            Action::Undo => self.undo(),
            Action::HomeView => {
                self.orbit = Orbit::default();
                self.show_view();
            }
            Action::Step => {
                if !self.running() {
                    // Queried at the new time, as any frame: exact at any rate.
                    self.world.show_at(self.time() + STEP * self.rate);
                    self.stepped(false);
                    self.retrace = true;
                }
            }
            Action::Graphs => {
                let on = !self.graphs_open();
                self.world.set_recording(on);
            }
            Action::GraphsCsv => self.save_graphs(),
            Action::Mute => {
                let said = self.hearing.toggle_mute();
                self.notify(said, notice::GOOD);
            }
            Action::Screenshot => return Effect::Screenshot,
            Action::Replay => return Effect::Replay,
            Action::Quit => return Effect::Quit,
        }
        Effect::Redraw
    }

    /// Changes the view by `change` (a drag or the wheel) and shows it, at one
    /// sample per pixel until the view rests ([`Self::settle`]).
    pub fn view(&mut self, change: ViewChange) {
        self.view_moved = Some(Instant::now());
        self.world.set_quality(1, None);
        match change {
            ViewChange::Turn(dx, dy) => self.orbit.turn(dx, dy),
            ViewChange::Pan(dx, dy) => self.orbit.pan(&self.config, dx, dy),
            ViewChange::Zoom(steps) => self.orbit.zoom(steps),
        }
        self.show_view();
    }

    /// Puts the user's view into the world; the next frame is traced in full.
    fn show_view(&mut self) {
        self.world
            .set_camera(self.orbit.camera(&self.config, self.fit_right));
        self.retrace = true;
    }

    /// Where the open control panel's left edge is (a share of the picture's
    /// width), or `None` once it is closed: the view fits the cradle left of
    /// it. Steps of 1/64 of the width, so the panel's own small changes of
    /// size do not move the view.
    pub fn set_panel_edge(&mut self, edge: Option<f32>) {
        let right = edge.map_or(FULL_WIDTH, |e| ((e - 0.01) * 64.0).floor() / 64.0);
        let right = right.clamp(0.3, FULL_WIDTH);
        if right != self.fit_right {
            self.fit_right = right;
            self.show_view();
        }
    }

    /// When the view, moved lately, will have rested: the next frame from then on
    /// is anti-aliased again (the window wakes for it).
    #[must_use]
    pub fn settle(&self) -> Option<Instant> {
        self.view_moved.map(|t| t + VIEW_REST)
    }

    /// Traces at the config's anti-aliasing from the next frame on.
    fn apply_quality(&mut self) {
        let r = &self.config.render;
        let adaptive = r.adaptive.then_some(r.adaptive_threshold as f32);
        self.world.set_quality(r.samples, adaptive);
    }

    /// Hidden time does not count: the swing resumes where it stopped. No click
    /// from before sounds after.
    pub fn hold_clock(&mut self) {
        self.last_frame = None;
        self.hearing.hush();
    }

    /// Paused time does not count either; the changed scene is traced again.
    fn restart_clock(&mut self) {
        self.hold_clock();
        self.retrace = true;
    }

    /// A new world for the current config from the start position, keeping the
    /// swing running if it was.
    fn respawn(&mut self) {
        self.custom = None;
        let running = self.running();
        self.world.respawn(&self.config);
        self.world.set_running(running);
        self.show_view();
        self.restart_clock();
    }

    /// Loads the config file again with the command line's overrides. A good one
    /// replaces the asset, after `resize` has taken its picture size; a bad one
    /// (or a refused size) keeps the running scene and is shown until the next.
    pub fn reload(&mut self, resize: impl FnOnce(u32, u32) -> Result<(), String>) {
        let loaded = self
            .source
            .load()
            .map_err(InputError::from)
            .and_then(|mut c| {
                self.overrides.apply(&mut c)?;
                Ok(c)
            });
        let config = match loaded {
            Ok(mut c) => {
                fit_window(&mut c);
                c
            }
            Err(e) => {
                tracing::error!("config not reloaded: {e}");
                self.error = Some(e.to_string());
                self.notify("reload refused: the error is shown above", notice::BAD);
                return;
            }
        };
        let (w, h) = (config.render.width, config.render.height);
        if (w, h) != (self.config.render.width, self.config.render.height)
            && let Err(e) = resize(w, h)
        {
            tracing::error!("cannot resize the framebuffer to {w}x{h}: {e}");
            self.error = Some(format!("framebuffer {w}x{h}: {e}"));
            self.notify("reload refused: the error is shown above", notice::BAD);
            return;
        }
        tracing::info!("reloaded {}", self.source);
        if config.render.threads != self.config.render.threads
            && let Ok(pool) = trace::pool(config.render.threads)
        {
            // Not while a frame traces on the old pool.
            self.tracer.join();
            self.pool = pool;
        }
        self.asset = config.clone();
        self.config = config;
        self.error = None;
        self.respawn();
        self.notify(format!("reloaded {}", self.source), notice::GOOD);
    }

    /// Shows `text` for a moment (a notice), in `color`.
    pub fn notify(&mut self, text: impl Into<String>, color: [u8; 3]) {
        self.notices.show(text, color, Instant::now());
    }

    /// When a notice on screen goes: the window wakes then to clear it.
    #[must_use]
    pub fn notice_expires(&self) -> Option<Instant> {
        self.notices.next_change()
    }

    /// Loads preset `index` of [`PRESETS`] in place of the asset (keeping the
    /// window's picture size), from its start position; Ctrl+Z undoes it.
    pub fn load_preset(&mut self, index: usize) {
        let Some(preset) = PRESETS.get(index) else {
            return;
        };
        match preset.config(&self.config) {
            Ok(c) => {
                self.remember();
                self.asset = c.clone();
                self.config = c;
                self.error = None;
                self.respawn();
                self.notify(format!("preset loaded: {}", preset.name), notice::GOOD);
            }
            Err(e) => {
                tracing::error!("preset {} not loaded: {e}", preset.name);
                self.notify(
                    format!("preset {} not loaded: {e}", preset.name),
                    notice::BAD,
                );
            }
        }
    }

    /// Writes the settings shown now as a new asset in the working directory
    /// (never replacing a file); a notice says where.
    pub fn save_setup(&mut self) {
        let stamp = super::screenshot::stamp_now();
        match presets::save_setup(&self.config, std::path::Path::new("."), &stamp) {
            Ok(path) => {
                let name = path.file_name().map_or_else(
                    || path.display().to_string(),
                    |n| n.to_string_lossy().into_owned(),
                );
                tracing::info!("saved setup {}", path.display());
                self.notify(
                    format!("saved setup {name} (run it: --config {name})"),
                    notice::GOOD,
                );
            }
            Err(e) => {
                tracing::error!("setup not saved: {e}");
                self.notify(format!("setup not saved: {e}"), notice::BAD);
            }
        }
    }

    /// Shift+G: writes what the graphs recorded as CSV,
    /// `newtons-cradle-YYYYMMDD-HHMMSS.csv` in the working directory (never
    /// over a file), and says where.
    pub fn save_graphs(&mut self) {
        let rec = self.world.recording();
        if rec.samples.is_empty() {
            self.notify(
                "nothing recorded: open the graphs (G) while it swings",
                notice::BAD,
            );
            return;
        }
        let text = crate::scene::record::csv(rec);
        let stamp = super::screenshot::stamp_now();
        let name =
            super::screenshot::free_named(&stamp, "csv", |n| std::path::Path::new(n).exists());
        match crate::export::write_all(std::path::Path::new(&name), text.as_bytes()) {
            Ok(()) => {
                tracing::info!("saved graphs {name}");
                self.notify(format!("saved graphs {name}"), notice::GOOD);
            }
            Err(e) => {
                tracing::error!("graphs not saved: {e}");
                self.notify(format!("graphs not saved: {e}"), notice::BAD);
            }
        }
    }

    /// Whether the graphs window is open (the physics records for it).
    #[must_use]
    pub fn graphs_open(&self) -> bool {
        self.world.recording().on
    }

    /// What the graphs read.
    #[must_use]
    pub fn recording(&self) -> &crate::scene::record::Recording {
        self.world.recording()
    }

    /// Whether egui draws anything: the panel or the graphs.
    #[must_use]
    pub fn egui_open(&self) -> bool {
        self.panel || self.graphs_open()
    }

    /// Keeps the state before a change of the panel's for Ctrl+Z.
    fn remember(&mut self) {
        let state = (self.asset.clone(), self.config.clone(), self.rate);
        self.history.record(state, Instant::now());
    }

    /// Ctrl+Z: back to the state before the panel's last change.
    fn undo(&mut self) {
        let Some((asset, config, rate)) = self.history.undo() else {
            self.notify("nothing to undo", notice::BAD);
            return;
        };
        self.rate = rate;
        self.asset = asset;
        let restart = !super::controls::absorbed(&self.config, &config);
        self.config = config;
        self.error = None;
        if restart {
            self.respawn();
        } else {
            self.apply_quality();
            self.retrace = true;
        }
        self.notify("undone: the last panel change", notice::GOOD);
    }

    /// While running, frames from now on trace on the pool one frame behind: the
    /// frame [`Self::step`] steps traces from [`Self::launch`] on, and the next
    /// step takes it back (what the window does, showing one frame while the
    /// next traces). Paused or changed scenes still trace at once.
    pub fn pipeline(&mut self) {
        self.tracer.pipeline();
    }

    /// Steps the world to `now` and traces, when something moves or changed
    /// (pipelined and running: leaves the frame for [`Self::launch`]). A frame
    /// launched before is taken back first.
    pub fn step(&mut self, now: Instant) {
        let mut traced = self.tracer.join();
        if self.settle().is_some_and(|t| now >= t) {
            self.view_moved = None;
            self.apply_quality();
            self.retrace = true;
        }
        let running = self.running();
        if running || self.retrace || self.tracer.image().is_none() {
            let dt = self
                .last_frame
                .map_or(0.0, |t| (now - t).as_secs_f64().min(MAX_FRAME_DT));
            // Slow or fast motion: the clock runs at the rate, and the physics is
            // queried at the clock's time, exact as ever; a cradle whose physics
            // cannot keep up shows the latest time it reached by the frame's
            // deadline, so the window keeps answering.
            let before = self.time();
            let want = if running { dt * self.rate } else { 0.0 };
            self.world.frame_by(want, Some(now + PHYSICS_BUDGET));
            self.behind = want > 0.0 && self.time() - before < 0.999 * want;
            let change = self.world.take_change();
            let now_traced = self
                .tracer
                .frame(&self.pool, (self.world.scene(), change), running);
            self.stepped(now_traced.is_none());
            traced = now_traced.or(traced);
            if running && dt > 0.0 {
                self.fps = smooth(self.fps, 1.0 / dt);
            }
            self.retrace = false;
        }
        if let Some(ms) = traced {
            if running && let Some(line) = self.rate_log.frame(now, ms) {
                tracing::info!("{line}");
            }
            self.trace_ms = smooth(self.trace_ms, ms);
        }
        if !running {
            self.rate_log.pause();
        }
        self.last_frame = running.then_some(now);
    }

    /// The last frame's impacts wait for the frame that shows them: the next
    /// step's if `pipelined`, else the one about to be presented.
    fn stepped(&mut self, pipelined: bool) {
        let impacts = self.world.impacts();
        let frame = (!impacts.impacts.is_empty()).then(|| Audible {
            t: self.time(),
            impacts: impacts.clone(),
        });
        self.hearing.stepped(frame, pipelined);
    }

    /// The impacts the frame being presented shows, with their simulated
    /// times: once each, none when muted.
    pub fn heard(&mut self) -> Vec<Audible> {
        self.hearing.take_shown()
    }

    /// How many times the swing stopped, restarted or was grabbed: the sound
    /// drops what it has not played yet when this changes.
    #[must_use]
    pub fn hushes(&self) -> u64 {
        self.hearing.hushes()
    }

    /// Muted (M, `--mute`).
    #[must_use]
    pub fn muted(&self) -> bool {
        self.hearing.muted()
    }

    /// The window is silent whatever M says, for `why` (no audio server).
    pub fn set_silent(&mut self, why: impl Into<String>) {
        self.hearing.set_silent(why);
    }

    /// Starts tracing the frame [`Self::step`] left (pipelined), if it left one;
    /// the next step takes it back.
    pub fn launch(&mut self) {
        self.tracer.launch_due(&self.pool, self.world.scene());
    }

    /// The flat scene of the last frame (its camera places the clicks).
    #[must_use]
    pub fn scene(&self) -> &crate::trace::Scene {
        self.world.scene()
    }

    /// The last picture traced.
    #[must_use]
    pub fn image(&self) -> Option<&Image> {
        self.tracer.image()
    }

    /// Which pixels the last picture's frame changed.
    #[must_use]
    pub fn changes(&self) -> Option<Changes<'_>> {
        self.tracer.changes()
    }

    /// Simulated time (s) of the last frame.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.world.cradle().snapshot.t
    }
}

use super::audible::{Audible, Hearing};

mod dragging;
mod editing;
mod rate_log;
mod status;
mod tracer;

pub use status::Overlay;

/// Exponential smoothing over ~10 frames keeps the HUD's numbers readable.
fn smooth(old: f64, new: f64) -> f64 {
    if old == 0.0 {
        new
    } else {
        0.9 * old + 0.1 * new
    }
}

#[cfg(test)]
mod tests;
