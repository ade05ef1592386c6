//! The user's view of the cradle between frames: the orbit (turns, pans and
//! zoom as offsets from the asset's camera), the region the cradle is fitted
//! into (left of the open control panel), and when the view last moved, so
//! that frames trace one sample per pixel while it moves and anti-alias again
//! once it rests for [`VIEW_REST`].

use crate::app::mouse::ViewChange;
use crate::app::orbit::Orbit;
use crate::config::Config;
use crate::trace::Camera;
use std::time::{Duration, Instant};

/// How long the view must rest before frames are anti-aliased again.
pub const VIEW_REST: Duration = Duration::from_millis(250);

/// The right edge of the fit region without the panel.
const FULL_WIDTH: f32 = 1.0 - crate::scene::view::FIT_SIDE;

/// The view: orbit, fit region, and whether it moves.
#[derive(Debug, Clone)]
pub struct Viewpoint {
    orbit: Orbit,
    /// The right edge (a share of the width) of the region the view fits the
    /// cradle into: left of the control panel while it is open.
    fit_right: f32,
    /// When the view last moved, until it has rested.
    moved: Option<Instant>,
}

impl Default for Viewpoint {
    fn default() -> Self {
        Self {
            orbit: Orbit::default(),
            fit_right: FULL_WIDTH,
            moved: None,
        }
    }
}

impl Viewpoint {
    /// The camera of this view of `config`'s cradle.
    #[must_use]
    pub fn camera(&self, config: &Config) -> Camera {
        self.orbit.camera(config, self.fit_right)
    }

    /// Moves the view by `change` (a drag or the wheel) at `now`.
    pub fn change(&mut self, config: &Config, change: ViewChange, now: Instant) {
        self.moved = Some(now);
        match change {
            ViewChange::Turn(dx, dy) => self.orbit.turn(dx, dy),
            ViewChange::Pan(dx, dy) => self.orbit.pan(config, dx, dy),
            ViewChange::Zoom(steps) => self.orbit.zoom(steps),
        }
    }

    /// Back to the asset's own camera.
    pub fn home(&mut self) {
        self.orbit = Orbit::default();
    }

    /// Fits the cradle left of `edge` (the open panel's left edge, a share of
    /// the picture's width), or the whole width once the panel is closed
    /// (`None`). Steps of 1/64 of the width, so the panel's own small changes
    /// of size do not move the view. True when the fit region changed.
    pub fn fit_left_of(&mut self, edge: Option<f32>) -> bool {
        let right = edge.map_or(FULL_WIDTH, |e| ((e - 0.01) * 64.0).floor() / 64.0);
        let right = right.clamp(0.3, FULL_WIDTH);
        let changed = right != self.fit_right;
        self.fit_right = right;
        changed
    }

    /// When the view, moved lately, will have rested.
    #[must_use]
    pub fn settle(&self) -> Option<Instant> {
        self.moved.map(|t| t + VIEW_REST)
    }

    /// Whether the view has come to rest by `now` (once: it then counts as
    /// unmoved).
    pub fn rested(&mut self, now: Instant) -> bool {
        let rested = self.settle().is_some_and(|t| now >= t);
        if rested {
            self.moved = None;
        }
        rested
    }
}

#[cfg(test)]
mod tests {
    use super::{FULL_WIDTH, VIEW_REST, Viewpoint};
    use crate::app::mouse::ViewChange;
    use crate::config::Config;
    use std::time::{Duration, Instant};

    #[test]
    fn the_fit_region_moves_in_64ths_and_only_when_it_changes() {
        let mut v = Viewpoint::default();
        assert!(!v.fit_left_of(None), "closed: already the full width");
        assert!(v.fit_left_of(Some(0.71)));
        // (0.71 - 0.01) * 64 = 44.8: 44/64.
        assert_eq!(v.fit_right, 44.0 / 64.0);
        assert!(
            !v.fit_left_of(Some(0.712)),
            "a panel a little wider moves nothing"
        );
        assert!(v.fit_left_of(Some(0.1)));
        assert_eq!(v.fit_right, 0.3, "at least 30% of the width");
        assert!(v.fit_left_of(None));
        assert_eq!(v.fit_right, FULL_WIDTH);
    }

    #[test]
    fn a_moved_view_rests_once_after_the_rest_time() {
        let (mut v, config, t0) = (Viewpoint::default(), Config::default(), Instant::now());
        let home = v.camera(&config);
        assert!(!v.rested(t0), "never moved");
        v.change(&config, ViewChange::Turn(30.0, 0.0), t0);
        assert_ne!(v.camera(&config), home, "a turn moves the camera");
        assert!(!v.rested(t0 + Duration::from_millis(249)));
        assert!(v.rested(t0 + VIEW_REST));
        assert!(!v.rested(t0 + VIEW_REST * 2), "once");
        v.home();
        assert_eq!(v.camera(&config), home);
    }
}
