//! The control panel (Tab): egui drawn over the picture in a second render pass
//! of pixels' frame, as pixels' `minimal-egui` example does. It shows and edits
//! the session's [`Controls`] and shows each ball's energy; what the edits do is
//! the session's rule, not the panel's.

use super::controls::Controls;
use super::session::Session;
use crate::config::{ContactModel, MAX_ANGLE_DEG, MAX_BALLS};
use crate::physics::Integrator;
use egui::{ClippedPrimitive, Context, TexturesDelta, ViewportId};
use egui_wgpu::{Renderer, RendererOptions, ScreenDescriptor};
use pixels::{Pixels, PixelsContext, wgpu};
use winit::window::Window;

/// egui's state over one window.
pub struct Panel {
    ctx: Context,
    state: egui_winit::State,
    screen: ScreenDescriptor,
    renderer: Renderer,
    paint_jobs: Vec<ClippedPrimitive>,
    textures: TexturesDelta,
}

impl Panel {
    /// A panel for `window`, drawing with `pixels`' device.
    pub fn new(window: &Window, pixels: &Pixels<'_>) -> Self {
        let ctx = Context::default();
        let size = window.inner_size();
        let scale = window.scale_factor() as f32;
        let max_side = pixels.device().limits().max_texture_dimension_2d as usize;
        let state = egui_winit::State::new(
            ctx.clone(),
            ViewportId::ROOT,
            window,
            Some(scale),
            None,
            Some(max_side),
        );
        Self {
            ctx,
            state,
            screen: ScreenDescriptor {
                size_in_pixels: [size.width.max(1), size.height.max(1)],
                pixels_per_point: scale,
            },
            renderer: Renderer::new(
                pixels.device(),
                pixels.render_texture_format(),
                RendererOptions::default(),
            ),
            paint_jobs: Vec::new(),
            textures: TexturesDelta::default(),
        }
    }

    /// Feeds a window event to egui; true when egui took it (a click on the
    /// panel is not a drag of the view).
    pub fn event(&mut self, window: &Window, event: &winit::event::WindowEvent) -> bool {
        self.state.on_window_event(window, event).consumed
    }

    /// The window's new size.
    pub fn resize(&mut self, width: u32, height: u32) {
        if width > 0 && height > 0 {
            self.screen.size_in_pixels = [width, height];
        }
    }

    /// Runs one egui frame over `session`: shows its settings and energies, and
    /// applies what the user changed. True when egui wants another frame soon
    /// (a new window is laid out on its second frame).
    pub fn prepare(&mut self, window: &Window, session: &mut Session) -> bool {
        let input = self.state.take_egui_input(window);
        let mut controls = session.controls();
        let before = controls.clone();
        let (shares, energy) = session.energies();
        let output = self.ctx.run_ui(input, |ui| {
            panel_ui(ui.ctx(), &mut controls, &shares, energy);
        });
        if controls != before {
            session.apply_controls(&controls);
        }
        self.textures.append(output.textures_delta);
        self.state
            .handle_platform_output(window, output.platform_output);
        self.paint_jobs = self
            .ctx
            .tessellate(output.shapes, self.screen.pixels_per_point);
        output
            .viewport_output
            .get(&ViewportId::ROOT)
            .is_some_and(|v| v.repaint_delay.is_zero())
    }

    /// Draws the panel over `target`, after pixels has drawn the picture.
    pub fn render(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        context: &PixelsContext<'_>,
    ) {
        for (id, delta) in &self.textures.set {
            self.renderer
                .update_texture(&context.device, &context.queue, *id, delta);
        }
        self.renderer.update_buffers(
            &context.device,
            &context.queue,
            encoder,
            &self.paint_jobs,
            &self.screen,
        );
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("panel"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    resolve_target: None,
                    depth_slice: None,
                    ops: wgpu::Operations {
                        // Over the picture pixels has just drawn.
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            self.renderer
                .render(&mut pass.forget_lifetime(), &self.paint_jobs, &self.screen);
        }
        for id in &std::mem::take(&mut self.textures).free {
            self.renderer.free_texture(id);
        }
    }
}

/// The panel's widgets.
fn panel_ui(ctx: &Context, c: &mut Controls, shares: &[f64], energy: (f64, f64)) {
    egui::Window::new("Controls")
        .anchor(egui::Align2::RIGHT_TOP, [-8.0, 8.0])
        .default_width(260.0)
        .show(ctx, |ui| {
            ui.add(egui::Slider::new(&mut c.balls, 1..=MAX_BALLS).text("balls"));
            let most = c.balls;
            ui.add(egui::Slider::new(&mut c.lift, 0..=most).text("lifted"));
            ui.add(
                egui::Slider::new(&mut c.angle_deg, 0.0..=MAX_ANGLE_DEG).text("lift angle (deg)"),
            );
            ui.add(egui::Slider::new(&mut c.gap, 0.0..=0.01).text("gap (m)"));
            ui.add(egui::Slider::new(&mut c.restitution, 0.0..=1.0).text("restitution"));
            egui::ComboBox::from_label("contact")
                .selected_text(c.contact.name())
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut c.contact, ContactModel::Ideal, "ideal");
                    ui.selectable_value(&mut c.contact, ContactModel::Hertz, "hertz");
                });
            ui.add(
                egui::Slider::new(&mut c.dissipation, 0.0..=1e-5)
                    .logarithmic(true)
                    .smallest_positive(1e-8)
                    .custom_formatter(|v, _| format!("{v:.2e}"))
                    .custom_parser(|s| s.trim().parse().ok())
                    .text("hertz dissipation (s)"),
            );
            ui.add(egui::Slider::new(&mut c.air_density, 0.0..=2.0).text("air density (kg/m^3)"));
            egui::ComboBox::from_label("integrator")
                .selected_text(c.integrator.name())
                .show_ui(ui, |ui| {
                    for i in Integrator::ALL {
                        ui.selectable_value(&mut c.integrator, i, i.name());
                    }
                });
            ui.add(egui::Slider::new(&mut c.samples, 1..=64).text("samples per pixel"));
            ui.checkbox(&mut c.adaptive, "adaptive anti-aliasing");
            ui.add(
                egui::Slider::new(&mut c.rate_exp, -4..=2)
                    .text("time rate")
                    .custom_formatter(|e, _| {
                        if e >= 0.0 {
                            format!("{}x", 2f64.powf(e))
                        } else {
                            format!("1/{}x", 2f64.powf(-e))
                        }
                    }),
            );
            ui.separator();
            let (left, error) = energy;
            ui.label(format!(
                "energy left {:.1}%, relative error {error:+.1e}",
                100.0 * left
            ));
            egui::ScrollArea::vertical()
                .max_height(200.0)
                .show(ui, |ui| {
                    for (i, share) in shares.iter().enumerate() {
                        ui.add(
                            egui::ProgressBar::new(share.clamp(0.0, 1.0) as f32)
                                .text(format!("ball {i}: {:.1}%", 100.0 * share)),
                        );
                    }
                });
        });
}
