//! The window-free session: run state, the user's controls, respawn and reload,
//! the clock between frames, and what the HUD says. The handler feeds it keys and
//! redraws; it steps the ECS world and the incremental tracer. Nothing here knows
//! of winit or pixels, so its rules are unit-tested without a display.

use super::controls::{Apply, Controls, History};
use super::drag;
use super::fit_window;
use super::keys::Action;
use super::mouse::ViewChange;
use super::notice::{self, Notices};
use super::presets::{self, PRESETS};
use crate::cli::{Common, InputError};
use crate::config::{Config, ConfigSource, MAX_BALLS};
use crate::scene::CradleWorld;
use crate::scene::components::Quality;
use crate::trace::{Changes, Image};
use std::time::Instant;

/// Longest simulated step of one frame (s): after a stall the swing continues
/// instead of jumping ahead.
pub const MAX_FRAME_DT: f64 = 0.25;

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
    /// The HUD's frame rates and the log's line every 2 s while running.
    rate_log: rate_log::RateLog,
    hud: HudMode,
    error: Option<String>,
    /// Simulated seconds per wall-clock second: a power of two, 1/16..=4.
    rate: f64,
    /// The user's view: orbit, fit region, whether it moves.
    view: Viewpoint,
    /// The ball being dragged, if one is.
    dragging: Option<usize>,
    /// The control panel is shown.
    panel: bool,
    /// What the user just did, shown for a moment.
    notices: Notices,
    /// The lifted balls of a drag to the right, which the config's start (balls
    /// lifted from the left) cannot say: "balls 4-5 at 31.0 deg right".
    custom: Option<String>,
    /// The states before the panel's last changes, for Ctrl+Z.
    history: History<(Config, Config, f64)>,
    /// The last frame's physics could not reach the clock's time within
    /// [`PHYSICS_BUDGET`]: the swing runs slower than the rate says.
    behind: bool,
    /// Impacts waiting for the frame that shows them, and the mute.
    hearing: Hearing,
}

/// The wall-clock time a frame's physics may take: past it, the frame shows
/// the latest state reached, and the swing runs slower than asked.
pub const PHYSICS_BUDGET: std::time::Duration = std::time::Duration::from_millis(50);

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
            pool: cores::pool(config.render.threads)?,
            world: CradleWorld::new(&config),
            asset: config.clone(),
            config,
            source,
            overrides,
            tracer: tracer::Tracer::default(),
            retrace: true,
            last_frame: None,
            rate_log: rate_log::RateLog::default(),
            hud: HudMode::Status,
            error: None,
            rate: 1.0,
            view: Viewpoint::default(),
            dragging: None,
            panel: false,
            notices: Notices::default(),
            custom: None,
            history: History::default(),
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
                self.view.home();
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

    /// Changes the view by `change` (a drag or the wheel) and shows it at
    /// [`Quality::MOVING`] (one ray per 2x2 block of pixels) until the view
    /// rests ([`Self::settle`]).
    pub fn view(&mut self, change: ViewChange) {
        self.view.change(&self.config, change, Instant::now());
        self.world.set_quality(Quality::MOVING);
        self.show_view();
    }

    /// Puts the user's view into the world; the next frame is traced in full.
    fn show_view(&mut self) {
        self.world.set_camera(self.view.camera(&self.config));
        self.retrace = true;
    }

    /// Where the open control panel's left edge is (a share of the picture's
    /// width), or `None` once it is closed: the view fits the cradle left of
    /// it ([`Viewpoint::fit_left_of`]).
    pub fn set_panel_edge(&mut self, edge: Option<f32>) {
        if self.view.fit_left_of(edge) {
            self.show_view();
        }
    }

    /// When the view, moved lately, will have rested: the next frame from then on
    /// is anti-aliased again (the window wakes for it).
    #[must_use]
    pub fn settle(&self) -> Option<Instant> {
        self.view.settle()
    }

    /// Traces at the config's anti-aliasing from the next frame on.
    fn apply_quality(&mut self) {
        self.world
            .set_quality(Quality::at_rest(&self.config.render));
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
            && let Ok(pool) = cores::pool(config.render.threads)
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
        match super::screenshot::save_named("csv", text.as_bytes()) {
            Ok(name) => {
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
        if self.view.rested(now) {
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
                self.rate_log.shown_after(dt);
            }
            self.retrace = false;
        }
        if let Some(ms) = traced
            && let Some(line) = self.rate_log.traced(now, ms, running)
        {
            tracing::info!("{line}");
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
    /// the next step takes it back. Until [`Self::give_back`], [`Self::image`]
    /// is still the last picture, while the frame prepares.
    pub fn launch(&mut self) {
        self.tracer.launch_due(&self.pool, self.world.scene());
    }

    /// Gives the last picture back to the frame [`Self::launch`] started, which
    /// waits for it to trace: call it once the picture is copied.
    pub fn give_back(&mut self) {
        self.tracer.give_back();
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

    /// A left press at picture pixel `at`: grabs the ball there, if any, and
    /// holds the swing while it is dragged. True when a ball was grabbed.
    pub fn grab(&mut self, at: (f64, f64)) -> bool {
        let snap = &self.world.cradle().snapshot;
        self.dragging = drag::pick(&self.config, &self.world.scene().camera, snap, at);
        if let Some(ball) = self.dragging {
            tracing::info!("picked ball {} at picture pixel {at:?}", ball + 1);
            self.world.set_running(false);
            self.restart_clock();
        }
        self.dragging.is_some()
    }

    /// The cursor at picture pixel `at` while a ball is held: the ball (with
    /// those between it and the end it is pulled to) hangs at the angle there,
    /// and the physics restarts from that state, exactly.
    /// True when a ball is held (the picture changes).
    pub fn drag_to(&mut self, at: (f64, f64)) -> bool {
        let Some(ball) = self.dragging else {
            return false;
        };
        let camera = self.world.scene().camera;
        tracing::debug!("ball {ball} dragged to picture pixel {at:?}");
        if let Some((theta, lifted, angle)) = drag::dragged(&self.config, &camera, ball, at) {
            self.world.start_from(&self.config, &theta, lifted, angle);
            self.show_dragged(ball, lifted, theta[ball]);
            self.retrace = true;
        }
        true
    }

    /// What the HUD and panel say after a drag that left `lifted` balls at
    /// angle `theta` (rad, signed), `ball` among them. Pulled left, the state
    /// is the config's own start (the leftmost balls lifted), and becomes it;
    /// pulled right, it is told as it is.
    fn show_dragged(&mut self, ball: usize, lifted: usize, theta: f64) {
        let deg = theta.abs().to_degrees();
        if theta <= 0.0 {
            self.config.start.lift = if theta == 0.0 { 0 } else { lifted };
            self.config.start.angle_deg = deg;
            self.custom = None;
        } else {
            let last = self.config.cradle.balls;
            let balls = if ball + 1 == last {
                format!("ball {last}")
            } else {
                format!("balls {}-{last}", ball + 1)
            };
            self.custom = Some(format!("{balls} at {deg:.1} deg right"));
        }
    }

    /// The ball held, if one is (numbered from 0 at the left).
    #[must_use]
    pub fn holding(&self) -> Option<usize> {
        self.dragging
    }

    /// What a drag to the right lifted ("balls 4-5 at 31.0 deg right"), which
    /// the config's start cannot say; `None` otherwise.
    #[must_use]
    pub fn custom_start(&self) -> Option<&str> {
        self.custom.as_deref()
    }

    /// The left button up: a held ball is let go, and the swing runs from there.
    pub fn release(&mut self) {
        if self.dragging.take().is_some() {
            self.world.set_running(true);
            self.restart_clock();
        }
    }

    /// Whether the control panel is shown.
    #[must_use]
    pub fn panel_open(&self) -> bool {
        self.panel
    }

    /// The control panel's settings now.
    #[must_use]
    pub fn controls(&self) -> Controls {
        Controls::of(&self.config, self.rate.log2().round() as i32)
    }

    /// Applies the control panel's settings ([`Controls::apply_to`]); a refused
    /// edit is shown in the HUD and changes nothing.
    pub fn apply_controls(&mut self, controls: &Controls) {
        let rate = 2f64.powi(controls.rate_exp.clamp(*RATES.start(), *RATES.end()));
        let applied = controls.apply_to(&self.config);
        if rate != self.rate || matches!(applied, Ok(Apply::Live(_) | Apply::Restart(_))) {
            self.remember();
        }
        self.rate = rate;
        match applied {
            Ok(Apply::Same) => {}
            Ok(Apply::Live(c)) => {
                self.config = c;
                self.apply_quality();
                self.retrace = true;
                self.error = None;
            }
            Ok(Apply::Restart(c)) => {
                self.config = c;
                self.error = None;
                self.respawn();
            }
            Err(e) => {
                let first = e.lines().next().unwrap_or_default().to_owned();
                self.notify(format!("not applied: {first}"), notice::BAD);
                self.error = Some(e);
            }
        }
    }

    /// Each ball's share of the starting energy; the share left in all, and its
    /// relative error (of the energy balance when the cradle dissipates).
    #[must_use]
    pub fn energies(&self) -> (Vec<f64>, (f64, f64)) {
        self.world.cradle().energies()
    }

    /// What to draw over the picture at `now` (notices past their time go).
    pub fn overlay(&mut self, now: Instant) -> Overlay {
        Overlay {
            status: self.hud_lines(),
            help: self.hud == HudMode::Help,
            notices: self.notices.at(now),
        }
    }

    /// Whether the HUD's status shows (screenshots then keep what the window
    /// shows; without it they are the bare picture).
    #[must_use]
    pub fn hud_on(&self) -> bool {
        self.hud != HudMode::Off
    }

    /// The lifted balls as the HUD and panel say it: the count and angle, or
    /// the balls and angle a drag to the right made.
    #[must_use]
    pub fn lifted_text(&self) -> String {
        match &self.custom {
            Some(custom) => format!("custom ({custom})"),
            None => format!(
                "{} at {:.1} deg",
                self.config.start.lift, self.config.start.angle_deg
            ),
        }
    }

    /// The HUD's status lines for its mode (none when off), plus any config error.
    #[must_use]
    pub fn hud_lines(&self) -> Vec<HudLine> {
        let cradle = self.world.cradle();
        let (params, snap) = (cradle.cradle.params(), &cradle.snapshot);
        let motion = match self.dragging {
            Some(ball) => Motion::Holding(ball),
            None if self.running() => {
                let (fps, trace_ms) = self.rate_log.shown();
                Motion::Running { fps, trace_ms }
            }
            None => Motion::Paused,
        };
        Readout {
            mode: self.hud,
            motion,
            time: self.time(),
            rate: self.rate,
            slowed: self.behind && self.running(),
            balls: self.config.cradle.balls,
            lifted: self.lifted_text(),
            model: self.config.contact.model.name(),
            energy: if params.dissipative() {
                Energy::Left(self.energies().1.0)
            } else {
                Energy::Error(cradle.cradle.energy_rel_error(snap))
            },
            momentum: params.momentum(&snap.theta, &snap.omega),
            muted: self.muted(),
            error: self.error.as_deref(),
        }
        .lines()
    }

    /// Simulated time (s) of the last frame.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.world.cradle().snapshot.t
    }
}

use super::audible::{Audible, Hearing};

mod cores;
mod rate_log;
mod status;
mod tracer;
mod view;

use status::{Energy, Motion, Readout};
pub use status::{HudLine, HudMode, Overlay};
use view::Viewpoint;

#[cfg(test)]
mod tests;
