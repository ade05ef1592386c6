//! The window: winit 0.30 + pixels 0.17 at the edge of the program.
//!
//! - [`session`]: window-free state and rules: run state, keys' actions, respawn,
//!   reload, the clock, the HUD's text. Each redraw it runs the ECS frame schedule
//!   (input -> physics -> extract) and traces the flat scene incrementally.
//! - `surface`: the window and the pixels framebuffer: resize, occlusion, present
//!   with the HUD ([`hud`]) drawn over the picture.
//! - `panel` (Tab): the egui control panel over the picture, editing the
//!   session's `controls`.
//! - `handler`: winit's event handler between the two.
//! - `keys`, `mouse`, `orbit`, `drag`: the key map, drags and wheel, the
//!   user's view, dragging balls.
//! - `reload`, `screenshot`: the config watcher, S's PNGs.
//! - `notice`, `presets`, `controls`: what an action did, shown for a moment;
//!   the panel's presets and saved setups; the panel's settings and undo.
//!
//! The window, pixels and event loop stay out of the World, the physics and the
//! tracer.

pub mod controls;
pub mod drag;
mod handler;
pub mod hud;
pub mod keys;
pub mod mouse;
pub mod notice;
pub mod orbit;
mod panel;
pub mod presets;
mod reload;
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

/// Shrinks the picture size of `config`, keeping its shape, to at most
/// [`MAX_WINDOW_PIXELS`]; the log says so when it does.
pub fn fit_window(config: &mut Config) {
    let r = &mut config.render;
    let pixels = f64::from(r.width) * f64::from(r.height);
    if pixels <= f64::from(MAX_WINDOW_PIXELS) {
        return;
    }
    let k = (f64::from(MAX_WINDOW_PIXELS) / pixels).sqrt();
    let (w, h) = (
        ((f64::from(r.width) * k) as u32).max(16),
        ((f64::from(r.height) * k) as u32).max(16),
    );
    tracing::warn!(
        "the window traces {w}x{h}, not {}x{}: at most 3840x2160 pixels keep it answering; `newtons-cradle render` takes any size",
        r.width,
        r.height
    );
    (r.width, r.height) = (w, h);
}

/// winit's errors start with the source file they came from; users need the rest.
fn plain(message: &str) -> String {
    let rest = match message.find(".rs:") {
        Some(i) => message[i..].split_once(": ").map_or(message, |(_, r)| r),
        None => message,
    };
    rest.trim_end_matches('.').to_string()
}
