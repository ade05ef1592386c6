//! The window's drawing surface: the winit window and the pixels framebuffer,
//! resizes, occlusion, and presenting a traced picture with the HUD over it.
//!
//! pixels 0.17.2 reconfigures its surface at the size it last knew and retries,
//! for ever, when the window has changed size since (parasyte/pixels#460). Checks
//! before `render()` narrow that window but cannot close it: a resize can land
//! while `render()` runs (it did, under Xvfb, when tracing starved the resizing
//! client). So pixels is patched, as upstream #462 does, to give up after a few
//! tries with `SurfaceOutdated`; then we wait for the size to settle and present
//! again. Besides, every non-zero size goes to `resize_surface`, nothing is
//! presented while resize events keep coming (until `RESIZE_SETTLE` after the
//! last), and the window's size is checked again right before each render.
//!
//! The traced bytes are sRGB already: where the surface offers a plain format,
//! pixels is built again with a plain texture and surface, and where the window
//! shows the picture pixel for pixel presenting copies the texture onto the
//! surface instead of drawing it (`formats`).

use super::WindowError;
use super::hud::{Canvas, scale_for};
use super::panel::Panel;
use super::session::{Overlay, Session};
use crate::trace::{Changes, Image};
use pixels::wgpu::TextureFormat;
use pixels::{Pixels, PixelsBuilder, SurfaceTexture};
use std::borrow::Cow;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::dpi::PhysicalSize;
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

/// Quiet time after the last resize event before presenting again.
const RESIZE_SETTLE: Duration = Duration::from_millis(150);

mod formats;
mod shown;
use formats::{copies, plain_of, put_bgra, scaling, texture_for};
use shown::Shown;

/// The window and its framebuffer.
pub struct Surface {
    window: Arc<Window>,
    pixels: Pixels<'static>,
    /// The control panel's egui state, made when it is first opened.
    panel: Option<Panel>,
    /// The size the surface was last configured at.
    size: (u32, u32),
    /// Minimised or hidden: nothing to draw.
    occluded: bool,
    /// When the last resize event came, while presenting waits for them to stop.
    resizing: Option<Instant>,
    /// The framebuffer holds BGRA bytes (for a `Bgra8Unorm` texture).
    bgra: bool,
    /// Which picture the framebuffer holds, and the HUD over it.
    shown: Shown,
}

impl Surface {
    /// Opens a window with a `width x height` framebuffer.
    ///
    /// # Errors
    /// No display, or no graphics adapter to draw with.
    pub fn create(event_loop: &ActiveEventLoop, width: u32, height: u32) -> anyhow::Result<Self> {
        let attrs = Window::default_attributes()
            .with_title("Newton's cradle")
            .with_inner_size(PhysicalSize::new(width, height));
        let window = Arc::new(
            event_loop
                .create_window(attrs)
                .map_err(|e| WindowError::NoDisplay(e.to_string()))?,
        );
        let size = window.inner_size();
        // SurfaceTexture::new asserts a non-zero size.
        let (sw, sh) = (size.width.max(1), size.height.max(1));
        let texture = || SurfaceTexture::new(sw, sh, Arc::clone(&window));
        let no_adapter = |e: pixels::Error| WindowError::NoAdapter(e.to_string());
        let mut pixels = Pixels::new(width, height, texture()).map_err(no_adapter)?;
        let offered = &pixels.context().surface_capabilities.formats;
        if let Some(plain) = plain_of(pixels.surface_texture_format(), offered) {
            // One surface per window: the first goes before the second is made.
            drop(pixels);
            pixels = PixelsBuilder::new(width, height, texture())
                .texture_format(texture_for(plain))
                .surface_texture_format(plain)
                .build()
                .or_else(|e| {
                    tracing::warn!("no {plain:?} surface after all ({e}); drawing through sRGB");
                    Pixels::new(width, height, texture())
                })
                .map_err(no_adapter)?;
        }
        pixels.set_scaling_mode(scaling((width, height), (sw, sh)));
        let bgra = pixels.context().texture_format == TextureFormat::Bgra8Unorm;
        tracing::info!(
            "window {sw}x{sh}, framebuffer {width}x{height}, format {:?}, texture {:?}",
            pixels.render_texture_format(),
            pixels.context().texture_format
        );
        window.request_redraw();
        Ok(Self {
            window,
            pixels,
            panel: None,
            size: (sw, sh),
            occluded: false,
            resizing: None,
            bgra,
            shown: Shown::default(),
        })
    }

    /// Asks for a redraw event.
    pub fn request_redraw(&self) {
        self.window.request_redraw();
    }

    /// Whether the window can be seen (not minimised or covered).
    #[must_use]
    pub fn visible(&self) -> bool {
        !self.occluded
    }

    /// The window was minimised (`true`) or shown again.
    pub fn set_occluded(&mut self, hidden: bool) {
        self.occluded = hidden;
        if !hidden {
            self.window.request_redraw();
        }
    }

    /// The window changed size: follow it, and hold presenting until it settles.
    pub fn resized(&mut self, size: PhysicalSize<u32>) {
        if let Some(p) = &mut self.panel {
            p.resize(size.width, size.height);
        }
        if size.width > 0 && size.height > 0 {
            let t = self.pixels.context().texture_extent;
            self.pixels
                .set_scaling_mode(scaling((t.width, t.height), (size.width, size.height)));
            match self.pixels.resize_surface(size.width, size.height) {
                Ok(()) => self.size = (size.width, size.height),
                Err(e) => tracing::warn!("cannot resize the surface to {size:?}: {e}"),
            }
        }
        self.resizing = Some(Instant::now());
    }

    /// A new framebuffer size (a reloaded asset's picture size).
    ///
    /// # Errors
    /// The GPU refused the texture, as text for the HUD.
    pub fn resize_buffer(&mut self, width: u32, height: u32) -> Result<(), String> {
        self.shown.forget();
        self.pixels
            .set_scaling_mode(scaling((width, height), self.size));
        self.pixels
            .resize_buffer(width, height)
            .map_err(|e| e.to_string())
    }

    /// The picture pixel under window position `(x, y)` (beyond the picture's
    /// edges when the window is, for drags that leave it).
    #[must_use]
    pub fn pixel(&self, (x, y): (f64, f64)) -> (f64, f64) {
        match self.pixels.window_pos_to_pixel((x as f32, y as f32)) {
            Ok((px, py)) => (px as f64, py as f64),
            Err((px, py)) => (px as f64, py as f64),
        }
    }

    /// Feeds an event to the control panel; true when it took it.
    pub fn panel_event(&mut self, event: &winit::event::WindowEvent) -> bool {
        self.panel
            .as_mut()
            .is_some_and(|p| p.event(&self.window, event))
    }

    /// The panel was hidden: its fields let go of the keyboard.
    pub fn close_panel(&mut self) {
        if let Some(p) = &mut self.panel {
            p.close();
        }
    }

    /// Runs the control panel's frame over `session` (before `present`); asks
    /// for another frame when egui wants one, and tells the session where
    /// the panel's left edge falls on the picture (the view keeps the cradle
    /// left of it).
    pub fn prepare_panel(&mut self, session: &mut Session) {
        let (window, pixels) = (&self.window, &self.pixels);
        let panel = self.panel.get_or_insert_with(|| Panel::new(window, pixels));
        let (again, left) = panel.prepare(window, session);
        if again {
            self.window.request_redraw();
        }
        let width = self.pixels.context().texture_extent.width;
        if let Some(left) = left {
            let (x, _) = self.pixel((f64::from(left), 0.0));
            session.set_panel_edge(Some((x / f64::from(width.max(1))) as f32));
        }
    }

    /// The framebuffer as last presented (the picture with the HUD): its
    /// size, whether its bytes are BGRA (else RGBA), and the bytes.
    #[must_use]
    pub fn raw_frame(&self) -> ((u32, u32), bool, &[u8]) {
        let t = self.pixels.context().texture_extent;
        ((t.width, t.height), self.bgra, self.pixels.frame())
    }

    /// Per row of the framebuffer, the pixels `x0..x1` the last frame wrote
    /// (`x0 >= x1`: none; `x1` may pass the width); `None` when any may have
    /// changed.
    #[must_use]
    pub fn touched(&self) -> Option<&[(u32, u32)]> {
        self.shown.touched()
    }

    /// The framebuffer as last presented (the picture with the HUD), RGBA.
    #[must_use]
    pub fn frame(&self) -> Cow<'_, [u8]> {
        let frame = self.pixels.frame();
        if self.bgra {
            // Swapping red and blue again gives the RGBA bytes back.
            let mut rgba = vec![0; frame.len()];
            put_bgra(&mut rgba, frame);
            Cow::Owned(rgba)
        } else {
            Cow::Borrowed(frame)
        }
    }

    /// While resizes keep coming: the time to wake and present again. Once they
    /// have settled, asks for a redraw and returns `None`.
    pub fn settle(&mut self) -> Option<Instant> {
        let until = self.resizing? + RESIZE_SETTLE;
        if Instant::now() < until {
            return Some(until);
        }
        self.resizing = None;
        self.window.request_redraw();
        None
    }

    /// Puts `image` (whose frame's `changes` say which pixels it changed, so
    /// that only those are copied) with the HUD's `overlay` over it in the
    /// framebuffer, for [`Self::draw`].
    pub fn upload(
        &mut self,
        image: Option<&Image>,
        changes: Option<Changes<'_>>,
        overlay: &Overlay,
    ) {
        let Some(img) = image else {
            return;
        };
        let frame = self.pixels.frame_mut();
        if frame.len() != img.rgba.len() {
            self.shown.forget();
            return;
        }
        self.shown.put(frame, img, changes, self.bgra);
        let mut canvas = Canvas {
            rgba: frame,
            width: img.width as usize,
            height: img.height as usize,
            bgra: self.bgra,
            scale: scale_for(img.width as usize, img.height as usize),
        };
        self.shown.hud(canvas.overlay(overlay));
    }

    /// Whether there is something to draw on (not hidden, not resizing), after
    /// checking the window's size once more (see the module docs; a round trip
    /// to the X server, so it is done while the next frame traces).
    fn drawable(&mut self) -> bool {
        let size = self.window.inner_size();
        if size.width == 0 || size.height == 0 || self.occluded || self.resizing.is_some() {
            return false;
        }
        if (size.width, size.height) != self.size {
            if let Err(e) = self.pixels.resize_surface(size.width, size.height) {
                tracing::error!("cannot resize the surface: {e}");
                return false;
            }
            self.size = (size.width, size.height);
        }
        true
    }

    /// Shows the framebuffer (after [`Self::upload`]), with the control panel
    /// when `panel` (prepared just before); nothing while hidden or resizing.
    ///
    /// # Errors
    /// Presenting failed for a reason other than a size change.
    pub fn draw(&mut self, panel: bool) -> anyhow::Result<()> {
        if !self.drawable() {
            return Ok(());
        }
        let ui = &mut self.panel;
        let c = self.pixels.context();
        let (t, size) = (c.texture_extent, self.size);
        let copy = copies(
            (c.texture_format, self.pixels.surface_texture_format()),
            c.surface_capabilities.usages,
            (t.width, t.height),
            size,
        );
        let drawn = self.pixels.render_with(|encoder, target, context| {
            if copy && (target.texture().width(), target.texture().height()) == size {
                let texture = context.texture.as_image_copy();
                encoder.copy_texture_to_texture(texture, target.texture().as_image_copy(), t);
            } else {
                context.scaling_renderer.render(encoder, target);
            }
            if let (true, Some(ui)) = (panel, ui.as_mut()) {
                ui.render(encoder, target, context);
            }
            Ok(())
        });
        match drawn {
            Ok(()) => Ok(()),
            Err(pixels::Error::SurfaceOutdated) => {
                // The window changed size during the render: wait for it to settle,
                // then present again at the size it has then.
                tracing::debug!("surface out of date; presenting again once the size settles");
                self.resizing = Some(Instant::now());
                Ok(())
            }
            Err(e) => Err(anyhow::anyhow!("presenting the frame failed: {e}")),
        }
    }
}
