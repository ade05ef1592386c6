//! The winit event handler: turns window events into calls on the [`Session`]
//! (keys, reload, redraw) and the [`Surface`] (resize, occlusion, present), and
//! decides when the loop sleeps: while paused it waits for an event, using no CPU.

use super::UserEvent;
use super::mouse::Mouse;
use super::replay::Replay;
use super::session::{Effect, Session};
use super::surface::Surface;
use super::{keys, notice, screenshot};
use crate::sound::{self, Sound};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoopProxy};
use winit::window::WindowId;

/// The running app: the session, and the window once it exists.
pub struct App {
    session: Session,
    surface: Option<Surface>,
    mouse: Mouse,
    /// Ctrl is held (Ctrl+Z).
    ctrl: bool,
    /// Wakes the loop from other threads (a screenshot saved).
    proxy: EventLoopProxy<UserEvent>,
    /// The clicks, on their own thread.
    sound: Sound,
    /// The session's hushes the sound has heard of.
    hushes: u64,
    /// The last seconds shown (V).
    replay: Replay,
    /// Why the loop was ended early, returned by `run`.
    pub failure: Option<anyhow::Error>,
}

impl App {
    /// An app for `session`; the window opens when the loop starts. Its
    /// frames trace while the one before is drawn ([`Session::pipeline`]).
    pub fn new(mut session: Session, proxy: EventLoopProxy<UserEvent>) -> Self {
        session.pipeline();
        let device = sound::output();
        if let Err(e) = &device {
            session.set_silent(format!("{e:#}"));
        }
        let sound = Sound::start(device, session.config().sound.volume, session.muted());
        Self {
            hushes: session.hushes(),
            session,
            surface: None,
            mouse: Mouse::default(),
            ctrl: false,
            proxy,
            sound,
            replay: Replay::start(),
            failure: None,
        }
    }

    /// Plays the clicks of the frame just presented; drops those not yet
    /// heard when the swing stopped, restarted or was grabbed since.
    fn hear(&mut self, shown: std::time::Instant) {
        if self.session.hushes() != self.hushes {
            self.hushes = self.session.hushes();
            self.sound.flush();
        }
        self.sound.set_muted(self.session.muted());
        self.sound.set_volume(self.session.config().sound.volume);
        let heard = self.session.heard();
        if heard.is_empty() {
            return;
        }
        let timbre = crate::sound::track::timbre(self.session.config());
        let scene = self.session.scene();
        let rate = self.session.rate();
        let clicks: Vec<_> = heard
            .iter()
            .flat_map(|a| a.clicks(&timbre, scene, rate))
            .collect();
        self.replay.clicks(clicks.clone());
        self.sound.play(clicks, shown);
    }

    /// Saves what the window shows: with the HUD on, the picture with it (and
    /// any notice); with the HUD off, the bare picture. A notice says where.
    fn screenshot(&self) {
        let Some(surface) = &self.surface else {
            return;
        };
        let r = &self.session.config().render;
        let proxy = self.proxy.clone();
        let done = move |saved| {
            // The loop has ended when this fails: nobody to tell.
            let _ = proxy.send_event(UserEvent::Saved(saved));
        };
        match self.session.image() {
            Some(img) if !self.session.hud_on() => {
                screenshot::save(img.width, img.height, &img.rgba, done);
            }
            _ => screenshot::save(r.width, r.height, &surface.frame(), done),
        }
    }

    /// Saves the last seconds shown, off the frame loop; a notice says where.
    fn keep(&mut self) {
        let proxy = self.proxy.clone();
        let done = move |kept| {
            // The loop has ended when this fails: nobody to tell.
            let _ = proxy.send_event(UserEvent::Kept(kept));
        };
        let png = super::replay::free_name(&screenshot::stamp_now());
        let timbre = crate::sound::track::timbre(self.session.config());
        self.session.notify(
            format!(
                "saving the last {:.0} s as {}",
                super::replay::SPAN,
                png.display()
            ),
            notice::GOOD,
        );
        self.replay.save(png, timbre, done);
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: anyhow::Error) {
        self.failure = Some(e);
        event_loop.exit();
    }

    /// Steps and presents a frame: the session's picture, the HUD, egui's
    /// windows; then the clicks of the impacts it shows.
    fn present(&mut self, event_loop: &ActiveEventLoop) {
        let Some(surface) = &mut self.surface else {
            return;
        };
        let (t_step, cpu_step) = (std::time::Instant::now(), thread_cpu());
        if surface.visible() {
            self.session.step(t_step);
        }
        let (step, cpu_step) = (t_step.elapsed(), thread_cpu() - cpu_step);
        let panel = self.session.egui_open();
        let t0 = std::time::Instant::now();
        let cpu0 = thread_cpu();
        if panel {
            surface.prepare_panel(&mut self.session);
        }
        let prep = t0.elapsed();
        let cpu_prep = thread_cpu() - cpu0;
        let t_up = std::time::Instant::now();
        let overlay = self.session.overlay(t_up);
        // The next frame traces while this one is drawn; it prepares while
        // this one's picture is copied to the framebuffer.
        self.session.launch();
        surface.upload(self.session.image(), self.session.changes(), &overlay);
        self.session.give_back();
        let up = t_up.elapsed();
        let t1 = std::time::Instant::now();
        let cpu1 = thread_cpu();
        let shows = surface.visible();
        let drawn = surface.draw(panel);
        // Every frame's writes reach the replay; it keeps those presented
        // while the swing runs.
        let keep = shows && drawn.is_ok() && self.session.running();
        let now = std::time::Instant::now();
        self.replay
            .frame(now, surface.raw_frame(), surface.touched(), keep);
        if let Err(e) = drawn {
            self.fail(event_loop, e);
        }
        // The main thread's cost of the step (the physics, the scene, taking
        // the last trace back: it waits for it), of the egui frame, of the
        // upload (launching the next trace, and the picture's changes and the
        // HUD into the framebuffer) and of presenting, in wall time and in
        // its own CPU time (a software renderer rasterises on threads of its
        // own, which the wall time waits for): `RUST_LOG=info,frame_cost=trace`.
        tracing::trace!(
            target: "frame_cost",
            "step {:.3} ms (cpu {:.3}), egui {:.3} ms (cpu {:.3}), upload {:.3} ms, present {:.3} ms (cpu {:.3})",
            step.as_secs_f64() * 1e3,
            cpu_step * 1e3,
            prep.as_secs_f64() * 1e3,
            cpu_prep * 1e3,
            up.as_secs_f64() * 1e3,
            t1.elapsed().as_secs_f64() * 1e3,
            (thread_cpu() - cpu1) * 1e3
        );
        self.hear(std::time::Instant::now());
    }

    fn redraw(&mut self) {
        if let Some(s) = &self.surface {
            s.request_redraw();
        }
    }
}

impl ApplicationHandler<UserEvent> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.surface.is_some() {
            return;
        }
        let r = &self.session.config().render;
        match Surface::create(event_loop, r.width, r.height) {
            Ok(s) => self.surface = Some(s),
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn user_event(&mut self, _event_loop: &ActiveEventLoop, event: UserEvent) {
        match event {
            UserEvent::Saved(Ok(name)) => {
                self.session
                    .notify(format!("saved screenshot {name}"), notice::GOOD);
                self.redraw();
            }
            UserEvent::Saved(Err(e)) => {
                self.session
                    .notify(format!("screenshot not saved: {e}"), notice::BAD);
                self.redraw();
            }
            UserEvent::Kept(Ok(kept)) => {
                let sound = kept
                    .wav
                    .as_ref()
                    .map_or(String::new(), |w| format!(" and {}", w.display()));
                self.session.notify(
                    format!(
                        "saved {:.1} s, {} frames: {}{sound}",
                        kept.seconds,
                        kept.frames,
                        kept.png.display()
                    ),
                    notice::GOOD,
                );
                self.redraw();
            }
            UserEvent::Kept(Err(e)) => {
                self.session
                    .notify(format!("last seconds not saved: {e}"), notice::BAD);
                self.redraw();
            }
            UserEvent::Reload => {
                let surface = &mut self.surface;
                self.session.reload(|w, h| match surface {
                    Some(s) => s.resize_buffer(w, h),
                    None => Ok(()),
                });
                self.redraw();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(surface) = &mut self.surface else {
            return;
        };
        // The panel sees events first; what it takes (a click on a slider, typing
        // in a field) is not ours. Keys reach it only while a field is edited,
        // and Tab never does (`Panel::event`).
        if self.session.egui_open() && surface.panel_event(&event) {
            surface.request_redraw();
            return;
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            // Destroyed from outside (another client's XDestroyWindow): nothing
            // left to draw on, so end as a close would, before touching it again.
            WindowEvent::Destroyed => {
                tracing::info!("the window was destroyed from outside; exiting");
                self.surface = None;
                event_loop.exit();
            }
            WindowEvent::Resized(size) => surface.resized(size),
            WindowEvent::Occluded(hidden) => {
                // Minimised on X11: no 0x0 resize, just this. Nothing to draw then.
                surface.set_occluded(hidden);
                self.session.hold_clock();
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
                let Some(action) =
                    keys::action(&event.logical_key, self.ctrl, self.mouse.shift_held())
                else {
                    return;
                };
                match self.session.act(action) {
                    Effect::Redraw => {}
                    Effect::Screenshot => self.screenshot(),
                    Effect::Replay => self.keep(),
                    Effect::Quit => event_loop.exit(),
                }
                if let Some(surface) = &mut self.surface {
                    // A hidden panel's fields let go of the keyboard.
                    if action == keys::Action::Panel && !self.session.panel_open() {
                        surface.close_panel();
                    }
                    surface.request_redraw();
                }
            }
            WindowEvent::ModifiersChanged(m) => {
                self.mouse.shift(m.state().shift_key());
                self.ctrl = m.state().control_key();
            }
            WindowEvent::MouseInput { button, state, .. } => {
                self.mouse.button(button, state);
                if button == MouseButton::Left {
                    match (state, self.mouse.at()) {
                        (ElementState::Pressed, Some(at)) => {
                            self.session.grab(surface.pixel(at));
                        }
                        (ElementState::Released, _) => self.session.release(),
                        _ => {}
                    }
                    surface.request_redraw();
                }
            }
            WindowEvent::CursorLeft { .. } => self.mouse.left(),
            WindowEvent::CursorMoved { position, .. } => {
                let held = self
                    .session
                    .drag_to(surface.pixel((position.x, position.y)));
                let change = self.mouse.moved(position.x, position.y);
                if let Some(change) = change {
                    self.session.view(change);
                }
                if held || change.is_some() {
                    surface.request_redraw();
                }
            }
            WindowEvent::MouseWheel { delta, .. } => {
                self.session.view(Mouse::wheel(delta));
                surface.request_redraw();
            }
            WindowEvent::RedrawRequested => self.present(event_loop),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(surface) = &mut self.surface else {
            return;
        };
        // Sleep until the resizes have settled, then draw at the final size.
        if let Some(until) = surface.settle() {
            event_loop.set_control_flow(ControlFlow::WaitUntil(until));
            return;
        }
        event_loop.set_control_flow(ControlFlow::Wait);
        // A view that moved lately is anti-aliased again once it rests.
        if let Some(until) = self.session.settle() {
            if std::time::Instant::now() < until {
                event_loop.set_control_flow(ControlFlow::WaitUntil(until));
            } else if surface.visible() {
                surface.request_redraw();
            }
        }
        // A notice on screen goes when its time is up, paused or not.
        if let Some(until) = self.session.notice_expires() {
            if std::time::Instant::now() < until {
                let sooner = match event_loop.control_flow() {
                    ControlFlow::WaitUntil(t) => t.min(until),
                    _ => until,
                };
                event_loop.set_control_flow(ControlFlow::WaitUntil(sooner));
            } else {
                surface.request_redraw();
            }
        }
        // Running: draw the next frame. Paused: wait for an event, using no CPU.
        if self.session.running() && surface.visible() {
            surface.request_redraw();
        }
    }
}

/// The calling thread's CPU time (s), 0 where the platform cannot say.
fn thread_cpu() -> f64 {
    cpu_time::ThreadTime::try_now().map_or(0.0, |t| t.as_duration().as_secs_f64())
}
