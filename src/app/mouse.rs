//! The mouse: which drags and wheel turns change the view. Right-drag turns it,
//! middle-drag (or Shift with right-drag) pans it, the wheel zooms. Window-free:
//! the handler feeds it winit's buttons, cursor and wheel.

use winit::event::{ElementState, MouseButton, MouseScrollDelta};

/// A change of the view, in window pixels or wheel steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ViewChange {
    /// Turn around the target by a drag of `(dx, dy)` pixels.
    Turn(f64, f64),
    /// Shift by a drag of `(dx, dy)` pixels.
    Pan(f64, f64),
    /// Nearer (positive) or further, in wheel steps.
    Zoom(f64),
}

/// The buttons held and where the cursor was.
#[derive(Debug, Default, Clone, Copy)]
pub struct Mouse {
    right: bool,
    middle: bool,
    shift: bool,
    at: Option<(f64, f64)>,
}

impl Mouse {
    /// A button went down or up.
    pub fn button(&mut self, button: MouseButton, state: ElementState) {
        let down = state == ElementState::Pressed;
        match button {
            MouseButton::Right => self.right = down,
            MouseButton::Middle => self.middle = down,
            _ => {}
        }
    }

    /// Shift went down or up.
    pub fn shift(&mut self, held: bool) {
        self.shift = held;
    }

    /// Whether Shift is held (Shift+G).
    #[must_use]
    pub fn shift_held(&self) -> bool {
        self.shift
    }

    /// The cursor moved to `(x, y)`: the view change a drag makes, if any.
    pub fn moved(&mut self, x: f64, y: f64) -> Option<ViewChange> {
        let last = self.at.replace((x, y))?;
        let (dx, dy) = (x - last.0, y - last.1);
        if self.middle || (self.right && self.shift) {
            Some(ViewChange::Pan(dx, dy))
        } else if self.right {
            Some(ViewChange::Turn(dx, dy))
        } else {
            None
        }
    }

    /// Where the cursor is (window pixels), if it is in the window.
    #[must_use]
    pub fn at(&self) -> Option<(f64, f64)> {
        self.at
    }

    /// The cursor left the window: the next move starts a new drag.
    pub fn left(&mut self) {
        self.at = None;
    }

    /// A wheel turn: a zoom in steps (a line, or 50 pixels of a touchpad).
    #[must_use]
    pub fn wheel(delta: MouseScrollDelta) -> ViewChange {
        ViewChange::Zoom(match delta {
            MouseScrollDelta::LineDelta(_, y) => f64::from(y),
            MouseScrollDelta::PixelDelta(p) => p.y / 50.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::{Mouse, ViewChange};
    use winit::event::{ElementState, MouseButton, MouseScrollDelta};

    #[test]
    fn drags_turn_or_pan_and_plain_moves_do_nothing() {
        let mut m = Mouse::default();
        assert_eq!(m.moved(10.0, 10.0), None, "no button: no change");
        m.button(MouseButton::Right, ElementState::Pressed);
        assert_eq!(m.moved(15.0, 8.0), Some(ViewChange::Turn(5.0, -2.0)));
        m.shift(true);
        assert_eq!(m.moved(16.0, 8.0), Some(ViewChange::Pan(1.0, 0.0)));
        m.shift(false);
        m.button(MouseButton::Right, ElementState::Released);
        m.button(MouseButton::Middle, ElementState::Pressed);
        assert_eq!(m.moved(16.0, 12.0), Some(ViewChange::Pan(0.0, 4.0)));
        m.left();
        assert_eq!(m.moved(100.0, 100.0), None, "re-entering starts a new drag");
        assert_eq!(
            Mouse::wheel(MouseScrollDelta::LineDelta(0.0, -2.0)),
            ViewChange::Zoom(-2.0)
        );
    }
}
