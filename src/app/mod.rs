//! The window: winit 0.30 + pixels 0.17 at the edge of the program. Each redraw runs
//! the ECS frame schedule (input -> physics -> extract), traces the flat scene into
//! the pixels framebuffer, draws the HUD over it and presents. The window, pixels
//! and event loop stay out of the World, the physics and the tracer.
//!
//! pixels 0.17.2 reconfigures its surface at the size it last knew and retries,
//! for ever, when the window has changed size since (parasyte/pixels#460). Checks
//! before `render()` narrow that window but cannot close it: a resize can land
//! while `render()` runs (it did, under Xvfb, when tracing starved the resizing
//! client). So pixels is patched, as upstream #462 does, to give up after a few
//! tries with `SurfaceOutdated`; then the app waits for the size to settle and
//! presents again. Besides, every non-zero size goes to `resize_surface`, nothing is
//! presented while resize events keep coming (until `RESIZE_SETTLE` after the
//! last), and the window's size is checked again right before each render.

pub mod hud;
mod keys;
mod reload;

use crate::cli::Common;
use crate::config::{Config, ConfigSource};
use crate::scene::{Control, CradleWorld, SimState};
use crate::trace::{self, Image};
use keys::Action;
use pixels::{Pixels, SurfaceTexture};
use std::sync::Arc;
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

/// Quiet time after the last resize event before presenting again.
const RESIZE_SETTLE: std::time::Duration = std::time::Duration::from_millis(150);

/// Longest simulated step of one frame (s): after a stall the swing continues
/// instead of jumping ahead.
const MAX_FRAME_DT: f64 = 0.25;

/// Events from outside the window.
#[derive(Debug, Clone, Copy)]
enum UserEvent {
    /// The config file was saved.
    Reload,
}

/// Why the window could not run.
#[derive(Debug, thiserror::Error)]
pub enum WindowError {
    /// No display to open a window on.
    #[error(
        "cannot open a window: {0}.\nThis needs a desktop session (DISPLAY or WAYLAND_DISPLAY). \
         Without one, render frames headless: `newtons-cradle render --out cradle.png` \
         (or `--gif cradle.gif`)"
    )]
    NoDisplay(String),
    /// The GPU side of the window failed (no adapter, no surface).
    #[error(
        "cannot draw into the window: {0}.\nNo usable graphics adapter (Vulkan, Metal, DX12 or GL) \
         was found. `newtons-cradle render --out cradle.png` works without one"
    )]
    NoAdapter(String),
}

/// Opens the window and runs until it closes.
///
/// # Errors
/// No display, no graphics adapter, or a failure of the event loop.
pub fn run(config: Config, source: ConfigSource, overrides: Common) -> anyhow::Result<()> {
    let event_loop = EventLoop::<UserEvent>::with_user_event()
        .build()
        .map_err(|e| WindowError::NoDisplay(plain(&e.to_string())))?;
    event_loop.set_control_flow(ControlFlow::Wait);
    let watcher = match &source {
        ConfigSource::File(path) => {
            match reload::watch(path, event_loop.create_proxy(), UserEvent::Reload) {
                Ok(w) => {
                    tracing::info!("watching {} for changes", path.display());
                    Some(w)
                }
                Err(e) => {
                    tracing::warn!("hot reload is off: cannot watch {}: {e}", path.display());
                    None
                }
            }
        }
        ConfigSource::Builtin => None,
    };
    let mut app = App::new(config, source, overrides)?;
    app.watcher = watcher;
    event_loop.run_app(&mut app)?;
    match app.failure.take() {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// What the HUD shows; H or F1 steps through them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum HudMode {
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

/// Smoothed frame statistics for the HUD.
#[derive(Debug, Default, Clone, Copy)]
struct Stats {
    fps: f64,
    trace_ms: f64,
}

struct App {
    /// The asset as loaded (with the command line's overrides): what R returns to.
    asset: Config,
    /// The asset with the user's changes (ball and lift counts).
    config: Config,
    source: ConfigSource,
    overrides: Common,
    world: CradleWorld,
    pool: rayon::ThreadPool,
    window: Option<Arc<Window>>,
    pixels: Option<Pixels<'static>>,
    surface: (u32, u32),
    /// Traces frames, re-tracing only what the swing can change.
    renderer: trace::Incremental,
    /// The scene changed while paused: trace once more.
    retrace: bool,
    last_frame: Option<Instant>,
    stats: Stats,
    hud: HudMode,
    error: Option<String>,
    occluded: bool,
    /// When the last resize event came, while presenting waits for them to stop.
    resizing: Option<Instant>,
    failure: Option<anyhow::Error>,
    watcher: Option<notify::RecommendedWatcher>,
}

impl App {
    fn new(config: Config, source: ConfigSource, overrides: Common) -> anyhow::Result<Self> {
        Ok(Self {
            pool: trace::pool(config.render.threads)?,
            world: CradleWorld::new(&config),
            asset: config.clone(),
            config,
            source,
            overrides,
            window: None,
            pixels: None,
            surface: (0, 0),
            renderer: trace::Incremental::new(),
            retrace: true,
            last_frame: None,
            stats: Stats::default(),
            hud: HudMode::Status,
            error: None,
            occluded: false,
            resizing: None,
            failure: None,
            watcher: None,
        })
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: anyhow::Error) {
        self.failure = Some(e);
        event_loop.exit();
    }

    fn create_window(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let (w, h) = (self.config.render.width, self.config.render.height);
        let attrs = Window::default_attributes()
            .with_title("Newton's cradle")
            .with_inner_size(PhysicalSize::new(w, h));
        let window = Arc::new(
            event_loop
                .create_window(attrs)
                .map_err(|e| WindowError::NoDisplay(e.to_string()))?,
        );
        let size = window.inner_size();
        // SurfaceTexture::new asserts a non-zero size.
        let (sw, sh) = (size.width.max(1), size.height.max(1));
        let pixels = Pixels::new(w, h, SurfaceTexture::new(sw, sh, Arc::clone(&window)))
            .map_err(|e| WindowError::NoAdapter(e.to_string()))?;
        tracing::info!(
            "window {sw}x{sh}, framebuffer {w}x{h}, format {:?}",
            pixels.render_texture_format()
        );
        self.surface = (sw, sh);
        self.pixels = Some(pixels);
        window.request_redraw();
        self.window = Some(window);
        Ok(())
    }

    fn running(&self) -> bool {
        self.world.state() == SimState::Running
    }

    fn act(&mut self, action: Action, event_loop: &ActiveEventLoop) {
        match action {
            Action::TogglePause => {
                self.world.send(Control::TogglePause);
                // Paused time does not count: the swing resumes where it stopped.
                self.last_frame = None;
                self.retrace = true;
            }
            Action::Reset => {
                // Back to the asset's start: its ball and lift counts too.
                self.config = self.asset.clone();
                self.world.respawn(&self.config);
                self.last_frame = None;
                self.retrace = true;
            }
            Action::Lift(d) => {
                let lift = self.config.start.lift as i64 + i64::from(d);
                if (0..=self.config.cradle.balls as i64).contains(&lift) {
                    self.config.start.lift = lift as usize;
                    self.respawn();
                }
            }
            Action::Balls(d) => {
                let balls = self.config.cradle.balls as i64 + i64::from(d);
                if (1..=200).contains(&balls) {
                    self.config.cradle.balls = balls as usize;
                    self.config.start.lift = self.config.start.lift.min(balls as usize);
                    self.respawn();
                }
            }
            Action::ToggleHud => {
                self.hud = self.hud.next();
            }
            Action::Screenshot => self.screenshot(),
            Action::Quit => event_loop.exit(),
        }
        if let Some(w) = &self.window {
            w.request_redraw();
        }
    }

    /// A new world for the current config, keeping the swing running if it was.
    fn respawn(&mut self) {
        let was_running = self.running();
        self.world.respawn(&self.config);
        self.world.show_at(0.0);
        if was_running != self.running() {
            self.world.send(Control::TogglePause);
        }
        self.last_frame = None;
        self.retrace = true;
    }

    fn reload(&mut self) {
        let loaded = self
            .source
            .load()
            .map_err(crate::cli::InputError::from)
            .and_then(|mut c| {
                self.overrides.apply(&mut c)?;
                Ok(c)
            });
        match loaded {
            Ok(config) => {
                tracing::info!("reloaded {}", self.source);
                if config.render.threads != self.config.render.threads
                    && let Ok(pool) = trace::pool(config.render.threads)
                {
                    self.pool = pool;
                }
                let (w, h) = (config.render.width, config.render.height);
                if let Some(p) = &mut self.pixels
                    && (w, h) != (self.config.render.width, self.config.render.height)
                    && let Err(e) = p.resize_buffer(w, h)
                {
                    tracing::error!("cannot resize the framebuffer to {w}x{h}: {e}");
                    self.error = Some(format!("framebuffer {w}x{h}: {e}"));
                    return;
                }
                self.asset = config.clone();
                self.config = config;
                self.error = None;
                self.respawn();
            }
            Err(e) => {
                // Keep the running scene; show what is wrong until the next save.
                tracing::error!("config not reloaded: {e}");
                self.error = Some(e.to_string());
            }
        }
        if let Some(w) = &self.window {
            w.request_redraw();
        }
    }

    fn screenshot(&self) {
        let Some(p) = &self.pixels else { return };
        let (w, h) = (self.config.render.width, self.config.render.height);
        let name = format!("newtons-cradle-{}.png", timestamp());
        let img = Image {
            width: w,
            height: h,
            rgba: p.frame().to_vec(),
        };
        match crate::export::write_png(std::path::Path::new(&name), &img) {
            Ok(()) => tracing::info!("saved screenshot {name}"),
            Err(e) => tracing::error!("screenshot not saved: {e}"),
        }
    }

    /// Steps the world and traces when something moves or changed.
    fn step(&mut self) {
        let now = Instant::now();
        let running = self.running();
        if running || self.retrace || self.renderer.image().is_none() {
            let dt = self
                .last_frame
                .map_or(0.0, |t| (now - t).as_secs_f64().min(MAX_FRAME_DT));
            self.world.frame(if running { dt } else { 0.0 });
            let start = Instant::now();
            let (pool, renderer, world) = (&self.pool, &mut self.renderer, &self.world);
            pool.install(|| {
                renderer.render(world.scene());
            });
            let ms = start.elapsed().as_secs_f64() * 1e3;
            if running && dt > 0.0 {
                // Exponential smoothing over ~10 frames keeps the numbers readable.
                let s = &mut self.stats;
                s.fps = if s.fps == 0.0 {
                    1.0 / dt
                } else {
                    0.9 * s.fps + 0.1 / dt
                };
            }
            self.stats.trace_ms = if self.stats.trace_ms == 0.0 {
                ms
            } else {
                0.9 * self.stats.trace_ms + 0.1 * ms
            };
            self.retrace = false;
        }
        self.last_frame = running.then_some(now);
    }

    fn hud_lines(&self) -> Vec<(String, [u8; 3])> {
        let white = [235, 235, 235];
        let snap = &self.world.cradle().snapshot;
        let err = self.world.cradle().cradle.energy_rel_error(snap);
        let state = if self.running() {
            "RUNNING"
        } else {
            "PAUSED - press SPACE"
        };
        let mut lines = vec![
            (
                format!("Newton's cradle   {state}"),
                if self.running() {
                    [140, 230, 140]
                } else {
                    [250, 210, 110]
                },
            ),
            (
                format!(
                    "fps {:5.1}   trace {:6.1} ms   t {:8.2} s",
                    self.stats.fps, self.stats.trace_ms, snap.t
                ),
                white,
            ),
            (
                format!(
                    "balls {}  lifted {}  contact {}  energy err {err:+.1e}",
                    self.config.cradle.balls,
                    self.config.start.lift,
                    self.config.contact.model.name()
                ),
                white,
            ),
        ];
        if self.hud == HudMode::Help {
            lines.extend(
                keys::HELP
                    .iter()
                    .map(|l| ((*l).to_string(), [180, 190, 200])),
            );
        } else {
            lines.push(("H: help".to_string(), [180, 190, 200]));
        }
        if let Some(e) = &self.error {
            for line in format!("config error: {e}").lines() {
                lines.push((line.to_string(), [255, 110, 100]));
            }
        }
        lines
    }

    fn present(&mut self, event_loop: &ActiveEventLoop) {
        let Some(window) = self.window.clone() else {
            return;
        };
        // Re-check the size right before rendering (see the module docs).
        let size = window.inner_size();
        if size.width == 0 || size.height == 0 || self.occluded || self.resizing.is_some() {
            return;
        }
        let lines = if self.hud != HudMode::Off || self.error.is_some() {
            self.hud_lines()
        } else {
            Vec::new()
        };
        let Some(pixels) = &mut self.pixels else {
            return;
        };
        if (size.width, size.height) != self.surface {
            if let Err(e) = pixels.resize_surface(size.width, size.height) {
                tracing::error!("cannot resize the surface: {e}");
                return;
            }
            self.surface = (size.width, size.height);
        }
        if let Some(img) = self.renderer.image() {
            let frame = pixels.frame_mut();
            if frame.len() == img.rgba.len() {
                frame.copy_from_slice(&img.rgba);
            }
            let (w, h) = (img.width as usize, img.height as usize);
            let mut canvas = hud::Canvas {
                rgba: frame,
                width: w,
                height: h,
            };
            if !lines.is_empty() {
                canvas.panel(0, &lines);
            }
        }
        match pixels.render() {
            Ok(()) => {}
            Err(pixels::Error::SurfaceOutdated) => {
                // The window changed size during the render: wait for it to settle,
                // then present again at the size it has then.
                tracing::debug!("surface out of date; presenting again once the size settles");
                self.resizing = Some(Instant::now());
            }
            Err(e) => self.fail(
                event_loop,
                anyhow::anyhow!("presenting the frame failed: {e}"),
            ),
        }
    }
}

impl ApplicationHandler<UserEvent> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_none()
            && let Err(e) = self.create_window(event_loop)
        {
            self.fail(event_loop, e);
        }
    }

    fn user_event(&mut self, _event_loop: &ActiveEventLoop, event: UserEvent) {
        match event {
            UserEvent::Reload => self.reload(),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if size.width > 0
                    && size.height > 0
                    && let Some(p) = &mut self.pixels
                {
                    match p.resize_surface(size.width, size.height) {
                        Ok(()) => self.surface = (size.width, size.height),
                        Err(e) => tracing::warn!("cannot resize the surface to {size:?}: {e}"),
                    }
                }
                self.resizing = Some(Instant::now());
            }
            WindowEvent::Occluded(hidden) => {
                // Minimised on X11: no 0x0 resize, just this. Nothing to draw then.
                self.occluded = hidden;
                self.last_frame = None;
                if !hidden && let Some(w) = &self.window {
                    w.request_redraw();
                }
            }
            WindowEvent::KeyboardInput {
                event,
                is_synthetic,
                ..
            } => {
                // winit re-sends held keys as synthetic presses on focus: not the user.
                if is_synthetic || event.state != ElementState::Pressed || event.repeat {
                    return;
                }
                if let Some(a) = keys::action(&event.logical_key) {
                    self.act(a, event_loop);
                }
            }
            WindowEvent::RedrawRequested => {
                if !self.occluded {
                    self.step();
                }
                self.present(event_loop);
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(w) = self.window.clone() else { return };
        if let Some(last) = self.resizing {
            // Sleep until the resizes have settled, then draw at the final size.
            let until = last + RESIZE_SETTLE;
            if Instant::now() < until {
                event_loop.set_control_flow(ControlFlow::WaitUntil(until));
                return;
            }
            self.resizing = None;
            w.request_redraw();
        }
        event_loop.set_control_flow(ControlFlow::Wait);
        // Running: draw the next frame. Paused: wait for an event, using no CPU.
        if self.running() && !self.occluded {
            w.request_redraw();
        }
    }
}

/// winit's errors start with the source file they came from; users need the rest.
fn plain(message: &str) -> String {
    let rest = match message.find(".rs:") {
        Some(i) => message[i..].split_once(": ").map_or(message, |(_, r)| r),
        None => message,
    };
    rest.trim_end_matches('.').to_string()
}

/// `YYYYMMDD-HHMMSS` in UTC, for screenshot names.
fn timestamp() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rem) = (secs / 86_400, secs % 86_400);
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}{month:02}{day:02}-{:02}{:02}{:02}",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}
