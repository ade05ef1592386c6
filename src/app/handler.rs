//! The winit event handler: turns window events into calls on the [`Session`]
//! (keys, reload, redraw) and the [`Surface`] (resize, occlusion, present), and
//! decides when the loop sleeps: while paused it waits for an event, using no CPU.

use super::UserEvent;
use super::mouse::Mouse;
use super::session::{Effect, Session};
use super::surface::Surface;
use super::{keys, screenshot};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::window::WindowId;

/// The running app: the session, and the window once it exists.
pub struct App {
    session: Session,
    surface: Option<Surface>,
    mouse: Mouse,
    /// Why the loop was ended early, returned by `run`.
    pub failure: Option<anyhow::Error>,
}

impl App {
    /// An app for `session`; the window opens when the loop starts. Its
    /// frames trace while the one before is drawn ([`Session::pipeline`]).
    pub fn new(mut session: Session) -> Self {
        session.pipeline();
        Self {
            session,
            surface: None,
            mouse: Mouse::default(),
            failure: None,
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: anyhow::Error) {
        self.failure = Some(e);
        event_loop.exit();
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
        // in a field) is not ours, but Tab always toggles it.
        let tab = matches!(&event, WindowEvent::KeyboardInput { event: k, .. }
            if k.logical_key == winit::keyboard::Key::Named(winit::keyboard::NamedKey::Tab));
        if self.session.panel_open() && surface.panel_event(&event) && !tab {
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
                let Some(action) = keys::action(&event.logical_key) else {
                    return;
                };
                match self.session.act(action) {
                    Effect::Redraw => {}
                    Effect::Screenshot => {
                        let r = &self.session.config().render;
                        screenshot::save(r.width, r.height, &surface.frame());
                    }
                    Effect::Quit => event_loop.exit(),
                }
                surface.request_redraw();
            }
            WindowEvent::ModifiersChanged(m) => self.mouse.shift(m.state().shift_key()),
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
            WindowEvent::RedrawRequested => {
                if surface.visible() {
                    self.session.step(std::time::Instant::now());
                }
                let panel = self.session.panel_open();
                if panel {
                    surface.prepare_panel(&mut self.session);
                }
                let lines = self.session.hud_lines();
                surface.upload(self.session.image(), self.session.changes(), &lines);
                // The next frame traces while this one is drawn.
                self.session.launch();
                if let Err(e) = surface.draw(panel) {
                    self.fail(event_loop, e);
                }
            }
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
        // Running: draw the next frame. Paused: wait for an event, using no CPU.
        if self.session.running() && surface.visible() {
            surface.request_redraw();
        }
    }
}
