//! The window: winit 0.30 + pixels 0.17 at the edge of the program.
//!
//! - [`session`]: window-free state and rules: run state, keys' actions, respawn,
//!   reload, the clock, the HUD's text. Each redraw it runs the ECS frame schedule
//!   (input -> physics -> extract) and traces the flat scene incrementally.
//! - `surface`: the window and the pixels framebuffer: resize, occlusion, present
//!   with the HUD ([`hud`]) drawn over the picture.
//! - `panel` (Tab): the egui control panel over the picture, editing the
//!   session's `controls`; `graphs` (G): plots of what the physics records.
//! - `handler`: winit's event handler between the two.
//! - `keys`, `mouse`, `orbit`, `drag`: the key map, drags and wheel, the
//!   user's view, dragging balls.
//! - `reload`, `screenshot`, [`replay`]: the config watcher, S's PNGs, V's
//!   last 10 seconds as an animated PNG (and WAV).
//! - `notice`, `presets`, `controls`: what an action did, shown for a moment;
//!   the panel's presets and saved setups; the panel's settings and undo.
//! - `audible`: each frame's impacts, held until the frame that shows them is
//!   presented, then made into clicks for the [`crate::sound`] thread.
//!
//! The window, pixels and event loop stay out of the World, the physics and the
//! tracer.

pub mod audible;
pub mod controls;
pub mod drag;
mod graphs;
mod handler;
pub mod hud;
pub mod keys;
pub mod mouse;
pub mod notice;
pub mod orbit;
mod panel;
pub mod presets;
mod reload;
pub mod replay;
pub mod screenshot;
pub mod session;
mod surface;

use crate::cli::Common;
use crate::config::{Config, ConfigSource};
use winit::event_loop::{ControlFlow, EventLoop};

/// Events from outside the window.
#[derive(Debug, Clone)]
enum UserEvent {
    /// The config file was saved.
    Reload,
    /// A screenshot was saved (its file name) or not (why).
    Saved(Result<String, String>),
    /// The last seconds were saved (V), or not (why).
    Kept(Result<replay::Saved, String>),
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
    // Kept alive while the loop runs: dropping it stops the watch.
    let _watcher = match &source {
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
    let mut app = handler::App::new(
        session::Session::new(config, source, overrides)?,
        event_loop.create_proxy(),
    );
    event_loop.run_app(&mut app)?;
    app.failure.map_or(Ok(()), Err)
}

/// The most pixels the window traces per frame (4K): beyond it a frame takes
/// seconds and the window stops answering keys. `render` takes any size.
pub const MAX_WINDOW_PIXELS: u32 = 3840 * 2160;

/// The share of pixels adaptive anti-aliasing supersamples (edges), for the
/// window's work estimate: 5 to 15% in the shipped scenes.
const EDGE_SHARE: f64 = 0.15;

/// The work of tracing one frame of `config`, in pixel-samples weighted by the
/// balls: samples per pixel (adaptive: only at edges), and 1 + balls / 40 for
/// the objects a ray meets on its way (measured: 394 instructions a pixel at
/// 5 balls, 2,048 at 200).
#[must_use]
pub fn window_work(config: &Config) -> f64 {
    let r = &config.render;
    let pixels = f64::from(r.width) * f64::from(r.height);
    pixels * samples_factor(r.samples, r.adaptive) * balls_factor(config.cradle.balls)
}

/// Samples traced per pixel on average.
fn samples_factor(samples: u32, adaptive: bool) -> f64 {
    let extra = f64::from(samples.max(1) - 1);
    if adaptive {
        1.0 + EDGE_SHARE * extra
    } else {
        1.0 + extra
    }
}

/// How much longer a ray takes among `balls` balls than among none.
fn balls_factor(balls: usize) -> f64 {
    1.0 + balls as f64 / 40.0
}

/// The most work a window frame may take ([`window_work`]): a 4K frame of the
/// default cradle at its default anti-aliasing, a fifth of a second on 2 cores.
#[must_use]
pub fn max_window_work() -> f64 {
    f64::from(MAX_WINDOW_PIXELS) * samples_factor(4, true) * balls_factor(5)
}

/// Keeps a window frame's work within [`max_window_work`] and its size within
/// [`MAX_WINDOW_PIXELS`]: fewer samples per pixel first, then a smaller
/// picture of the same shape; the log says so when it does. Escape and every
/// key then answer within a frame.
pub fn fit_window(config: &mut Config) {
    let (w0, h0, s0) = (
        config.render.width,
        config.render.height,
        config.render.samples,
    );
    let most = max_window_work();
    let per_pixel = balls_factor(config.cradle.balls);
    let r = &mut config.render;
    while r.samples > 1 && window_work_of(r, per_pixel) > most {
        r.samples -= 1;
    }
    let pixels = f64::from(r.width) * f64::from(r.height);
    let work = window_work_of(r, per_pixel);
    let k = (f64::from(MAX_WINDOW_PIXELS) / pixels)
        .min(most / work)
        .sqrt();
    if k < 1.0 {
        r.width = ((f64::from(r.width) * k) as u32).max(16);
        r.height = ((f64::from(r.height) * k) as u32).max(16);
    }
    if (r.width, r.height, r.samples) != (w0, h0, s0) {
        tracing::warn!(
            "the window traces {}x{} at {} samples per pixel, not {w0}x{h0} at {s0}: \
             at most a 4K frame of the default cradle's work keeps it answering; \
             `newtons-cradle render` takes any size",
            r.width,
            r.height,
            r.samples
        );
    }
}

/// [`window_work`] of `r` with `per_pixel` for the balls.
fn window_work_of(r: &crate::config::RenderConfig, per_pixel: f64) -> f64 {
    f64::from(r.width) * f64::from(r.height) * samples_factor(r.samples, r.adaptive) * per_pixel
}

/// winit's errors start with the source file they came from; users need the rest.
fn plain(message: &str) -> String {
    let rest = match message.find(".rs:") {
        Some(i) => message[i..].split_once(": ").map_or(message, |(_, r)| r),
        None => message,
    };
    rest.trim_end_matches('.').to_string()
}
