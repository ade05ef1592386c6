//! The control panel (Tab): egui drawn over the picture in a second render pass
//! of pixels' frame, as pixels' `minimal-egui` example does. It shows and edits
//! the session's [`Controls`] and shows each ball's energy; what the edits do is
//! the session's rule, not the panel's.

use super::controls::Controls;
use super::graphs::{Graphs, graphs_ui};
use super::presets::PRESETS;
use super::session::Session;
use crate::config::{ContactModel, ranges};
use crate::physics::Integrator;
use egui::{ClippedPrimitive, Context, TexturesDelta, ViewportId};
use egui_wgpu::{Renderer, RendererOptions, ScreenDescriptor};
use pixels::{Pixels, PixelsContext, wgpu};
use winit::keyboard::{Key, NamedKey};
use winit::window::Window;

/// egui's state over one window.
pub struct Panel {
    ctx: Context,
    state: egui_winit::State,
    screen: ScreenDescriptor,
    renderer: Renderer,
    paint_jobs: Vec<ClippedPrimitive>,
    textures: TexturesDelta,
    /// A text field (a slider's typed value) had the keyboard at the end of
    /// the last frame: only then do keys go to the panel.
    editing: bool,
    /// The graphs window's own state.
    graphs: Graphs,
}

impl Panel {
    /// A panel for `window`, drawing with `pixels`' device.
    pub fn new(window: &Window, pixels: &Pixels<'_>) -> Self {
        let ctx = Context::default();
        // No shadows under the windows: a shadow is a wide blurred band of
        // blended pixels, a third of what a software renderer (lavapipe) spends
        // drawing the panel.
        ctx.global_style_mut(|s| {
            s.visuals.window_shadow = egui::epaint::Shadow::NONE;
            s.visuals.popup_shadow = egui::epaint::Shadow::NONE;
        });
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
                // Without dithering's noise per pixel: the panel's flat
                // colours do not band, and a software renderer saves its cost.
                RendererOptions {
                    dithering: false,
                    ..RendererOptions::default()
                },
            ),
            paint_jobs: Vec::new(),
            textures: TexturesDelta::default(),
            editing: false,
            graphs: Graphs::default(),
        }
    }

    /// Feeds a window event to egui; true when egui took it (a click on the
    /// panel is not a drag of the view). Keys go to egui only while a text
    /// field is being edited, and Tab never does: it is the app's key for the
    /// panel, and egui would walk its focus through the fields with it.
    pub fn event(&mut self, window: &Window, event: &winit::event::WindowEvent) -> bool {
        if let winit::event::WindowEvent::KeyboardInput { event: key, .. } = event
            && (!self.editing || key.logical_key == Key::Named(NamedKey::Tab))
        {
            return false;
        }
        self.state.on_window_event(window, event).consumed
    }

    /// The panel was hidden: no field keeps the keyboard.
    pub fn close(&mut self) {
        self.ctx.memory_mut(egui::Memory::stop_text_input);
        self.editing = false;
    }

    /// The window's new size.
    pub fn resize(&mut self, width: u32, height: u32) {
        if width > 0 && height > 0 {
            self.screen.size_in_pixels = [width, height];
        }
    }

    /// Runs one egui frame over `session`: shows its settings and energies
    /// (the panel open) and its graphs (the graphs open), and applies what the
    /// user changed. Returns whether egui wants another frame soon (a new window
    /// is laid out on its second frame), and the panel's left edge in window
    /// pixels (`None` with the panel closed).
    pub fn prepare(&mut self, window: &Window, session: &mut Session) -> (bool, Option<f32>) {
        let input = self.state.take_egui_input(window);
        // The plots' lines, anti-aliased by feathering, cost a software
        // renderer (lavapipe) 5 ms a frame: the graphs draw them without it.
        let plain = session.graphs_open();
        self.ctx.tessellation_options_mut(|o| o.feathering = !plain);
        let mut controls = session.controls();
        let before = controls.clone();
        let (shares, energy) = session.energies();
        let custom = session.custom_start().map(str::to_owned);
        let mut request = None;
        let mut left = None;
        let mut muted = session.muted();
        let (panel, mut graphs) = (session.panel_open(), session.graphs_open());
        let graphs_state = &mut self.graphs;
        let recording = session.recording();
        let output = self.ctx.run_ui(input, |ui| {
            if panel {
                let shown = Shown {
                    custom: custom.as_deref(),
                    shares: &shares,
                    energy,
                };
                (request, left) = panel_ui(ui.ctx(), &mut controls, &mut muted, &shown);
            }
            if graphs {
                graphs_ui(ui.ctx(), recording, graphs_state, &mut graphs);
            }
        });
        if muted != session.muted() {
            session.act(crate::app::keys::Action::Mute);
        }
        if graphs != session.graphs_open() {
            session.act(crate::app::keys::Action::Graphs);
        }
        if controls != before {
            session.apply_controls(&controls);
        }
        match request {
            Some(Request::Preset(i)) => session.load_preset(i),
            Some(Request::SaveSetup) => session.save_setup(),
            Some(Request::Undo) => {
                session.act(crate::app::keys::Action::Undo);
            }
            None => {}
        }
        self.editing = self.ctx.text_edit_focused();
        self.textures.append(output.textures_delta);
        self.state
            .handle_platform_output(window, output.platform_output);
        self.paint_jobs = self
            .ctx
            .tessellate(output.shapes, self.screen.pixels_per_point);
        let again = output
            .viewport_output
            .get(&ViewportId::ROOT)
            .is_some_and(|v| v.repaint_delay.is_zero());
        (again, left.map(|l| l * self.screen.pixels_per_point))
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

/// What the panel asks of the session besides its settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Request {
    /// Load preset `i` of [`PRESETS`].
    Preset(usize),
    /// Write the settings as a new asset.
    SaveSetup,
    /// Back to the state before the last change (as Ctrl+Z).
    Undo,
}

/// What the panel shows besides the settings it edits.
struct Shown<'a> {
    /// What a drag to the right lifted.
    custom: Option<&'a str>,
    /// Each ball's share of the energy.
    shares: &'a [f64],
    /// The energy left, and its error.
    energy: (f64, f64),
}

/// The panel's widgets, editing the settings and the mute. Returns what the
/// user asked for, and the panel's left edge (points).
fn panel_ui(
    ctx: &Context,
    c: &mut Controls,
    muted: &mut bool,
    shown: &Shown<'_>,
) -> (Option<Request>, Option<f32>) {
    let Shown {
        custom,
        shares,
        energy,
    } = *shown;
    let mut request = None;
    let shown = egui::Window::new("Controls")
        .anchor(egui::Align2::RIGHT_TOP, [-8.0, 8.0])
        .default_width(260.0)
        .show(ctx, |ui| {
            request = presets_row(ui);
            ui.separator();
            // Every slider spans its key's whole range (`config::ranges`), and
            // a typed value is passed on as typed: validation refuses what is
            // out of range, and says so, rather than the slider clamping it.
            let never = egui::SliderClamping::Never;
            ui.add(
                egui::Slider::new(&mut c.balls, ranges::BALLS)
                    .logarithmic(true)
                    .clamping(never)
                    .text("balls"),
            );
            let most = c.balls;
            ui.add(
                egui::Slider::new(&mut c.lift, 0..=most)
                    .clamping(never)
                    .text("lifted"),
            );
            if let Some(custom) = custom {
                ui.label(format!("now lifted by a drag: {custom}"));
            }
            ui.add(
                egui::Slider::new(&mut c.angle_deg, ranges::ANGLE_DEG)
                    .clamping(never)
                    .text("lift angle (deg)"),
            );
            ui.add(
                egui::Slider::new(&mut c.gap, ranges::GAP)
                    .logarithmic(true)
                    .smallest_positive(1e-5)
                    .clamping(never)
                    .text("gap (m)"),
            );
            ui.add(
                egui::Slider::new(&mut c.restitution, ranges::RESTITUTION)
                    .clamping(never)
                    .text("restitution"),
            );
            egui::ComboBox::from_label("contact")
                .selected_text(c.contact.name())
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut c.contact, ContactModel::Ideal, "ideal");
                    ui.selectable_value(&mut c.contact, ContactModel::Hertz, "hertz");
                });
            ui.add(
                egui::Slider::new(&mut c.dissipation, ranges::DISSIPATION)
                    .logarithmic(true)
                    .smallest_positive(1e-9)
                    .clamping(never)
                    .custom_formatter(|v, _| format!("{v:.2e}"))
                    .custom_parser(|s| s.trim().parse().ok())
                    .text("hertz dissipation (s)"),
            );
            ui.add(
                egui::Slider::new(&mut c.air_density, ranges::AIR_DENSITY)
                    .logarithmic(true)
                    .smallest_positive(0.01)
                    .clamping(never)
                    .text("air density (kg/m^3)"),
            );
            egui::ComboBox::from_label("integrator")
                .selected_text(c.integrator.name())
                .show_ui(ui, |ui| {
                    for i in Integrator::ALL {
                        ui.selectable_value(&mut c.integrator, i, i.name());
                    }
                });
            ui.add(
                egui::Slider::new(&mut c.samples, ranges::SAMPLES)
                    .clamping(never)
                    .text("samples per pixel"),
            );
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
            sound_row(ui, &mut c.volume, muted);
            ui.separator();
            energy_bars(ui, shares, energy);
        });
    (request, shown.map(|s| s.response.rect.left()))
}

/// The clicks' volume and the mute.
fn sound_row(ui: &mut egui::Ui, volume: &mut f64, muted: &mut bool) {
    ui.horizontal(|ui| {
        ui.add(
            egui::Slider::new(volume, ranges::VOLUME)
                .clamping(egui::SliderClamping::Never)
                .text("volume"),
        );
        ui.checkbox(muted, "mute (M)");
    });
}

/// The presets list, "save setup" and "undo": what the user asked, if anything.
fn presets_row(ui: &mut egui::Ui) -> Option<Request> {
    let mut request = None;
    ui.horizontal(|ui| {
        egui::ComboBox::from_id_salt("preset")
            .selected_text("load a preset")
            .show_ui(ui, |ui| {
                for (i, p) in PRESETS.iter().enumerate() {
                    if ui.selectable_label(false, p.name).clicked() {
                        request = Some(Request::Preset(i));
                    }
                }
            });
        if ui
            .button("save setup")
            .on_hover_text("write these settings as a new .ron asset in the working folder")
            .clicked()
        {
            request = Some(Request::SaveSetup);
        }
        if ui.button("undo").on_hover_text("Ctrl+Z").clicked() {
            request = Some(Request::Undo);
        }
    });
    request
}

/// The energy left with its error, and each ball's share as a bar.
fn energy_bars(ui: &mut egui::Ui, shares: &[f64], (left, error): (f64, f64)) {
    ui.label(format!(
        "energy left {:.1}%, relative error {error:+.1e}",
        100.0 * left
    ));
    egui::ScrollArea::vertical()
        .max_height(200.0)
        .show(ui, |ui| {
            for (i, share) in shares.iter().enumerate() {
                let share = share.clamp(0.0, 1.0) as f32;
                let mut bar = egui::ProgressBar::new(share).text(format!(
                    "ball {}: {:.1}%",
                    i + 1,
                    100.0 * share
                ));
                // egui draws at least a bar's height of fill: a ball at
                // rest would show a stub.
                if share < 0.005 {
                    bar = bar.fill(egui::Color32::TRANSPARENT);
                }
                ui.add(bar);
            }
        });
}

#[cfg(test)]
mod tests {
    use super::{Shown, panel_ui};
    use crate::app::controls::Controls;
    use crate::config::{Config, ContactModel, ranges};

    /// The panel's settings after `frames` frames of egui with no input.
    fn shown(controls: &Controls, frames: usize) -> Controls {
        let ctx = egui::Context::default();
        let mut c = controls.clone();
        for _ in 0..frames {
            let _ = ctx.run_ui(egui::RawInput::default(), |ui| {
                let shown = Shown {
                    custom: None,
                    shares: &[0.5, 0.5],
                    energy: (1.0, 0.0),
                };
                panel_ui(ui.ctx(), &mut c, &mut false, &shown);
            });
        }
        c
    }

    #[test]
    fn opening_the_panel_moves_no_value_the_config_accepts() {
        // Each key at the top of its range, and a cradle of a 5 cm gap with
        // air at 50 kg/m^3, as the command line may set them: the panel shows
        // them as they are (its sliders once clamped them to 1 cm, 2 kg/m^3).
        let mut config = Config::default();
        config.cradle.balls = *ranges::BALLS.end();
        config.start.lift = 3;
        config.start.angle_deg = *ranges::ANGLE_DEG.end();
        config.cradle.gap = *ranges::GAP.end();
        config.contact.model = ContactModel::Hertz;
        config.cradle.air_density = *ranges::AIR_DENSITY.end();
        config.contact.dissipation = config.dissipation_limit().0;
        config.render.samples = *ranges::SAMPLES.end();
        config.sound.volume = *ranges::VOLUME.end();
        let mut wide = Config::default();
        wide.cradle.gap = 0.05;
        wide.contact.model = ContactModel::Hertz;
        wide.cradle.air_density = 50.0;
        for c in [config, wide, Config::default()] {
            assert!(c.validate().is_ok());
            let controls = Controls::of(&c, 0);
            assert_eq!(shown(&controls, 3), controls);
        }
    }
}
