//! Dragging a ball, for the session: grab under the cursor, hang at the angle
//! under it, let go ([`super::drag`] does the geometry).

use super::Session;
use crate::app::drag;

impl Session {
    /// A left press at picture pixel `at`: grabs the ball there, if any, and
    /// holds the swing while it is dragged. True when a ball was grabbed.
    pub fn grab(&mut self, at: (f64, f64)) -> bool {
        let snap = &self.world.cradle().snapshot;
        self.dragging = drag::pick(&self.config, &self.world.scene().camera, snap, at);
        if let Some(ball) = self.dragging {
            tracing::info!("picked ball {} at picture pixel {at:?}", ball + 1);
            self.world.set_running(false);
            self.restart_clock();
        }
        self.dragging.is_some()
    }

    /// The cursor at picture pixel `at` while a ball is held: the ball (with
    /// those between it and the end it is pulled to) hangs at the angle there,
    /// and the physics restarts from that state, exactly.
    /// True when a ball is held (the picture changes).
    pub fn drag_to(&mut self, at: (f64, f64)) -> bool {
        let Some(ball) = self.dragging else {
            return false;
        };
        let camera = self.world.scene().camera;
        tracing::debug!("ball {ball} dragged to picture pixel {at:?}");
        if let Some((theta, lifted, angle)) = drag::dragged(&self.config, &camera, ball, at) {
            self.world.start_from(&self.config, &theta, lifted, angle);
            self.show_dragged(ball, lifted, theta[ball]);
            self.retrace = true;
        }
        true
    }

    /// What the HUD and panel say after a drag that left `lifted` balls at
    /// angle `theta` (rad, signed), `ball` among them. Pulled left, the state
    /// is the config's own start (the leftmost balls lifted), and becomes it;
    /// pulled right, it is told as it is.
    fn show_dragged(&mut self, ball: usize, lifted: usize, theta: f64) {
        let deg = theta.abs().to_degrees();
        if theta <= 0.0 {
            self.config.start.lift = if theta == 0.0 { 0 } else { lifted };
            self.config.start.angle_deg = deg;
            self.custom = None;
        } else {
            let last = self.config.cradle.balls;
            let balls = if ball + 1 == last {
                format!("ball {last}")
            } else {
                format!("balls {}-{last}", ball + 1)
            };
            self.custom = Some(format!("{balls} at {deg:.1} deg right"));
        }
    }

    /// The ball held, if one is (numbered from 0 at the left).
    #[must_use]
    pub fn holding(&self) -> Option<usize> {
        self.dragging
    }

    /// What a drag to the right lifted ("balls 4-5 at 31.0 deg right"), which
    /// the config's start cannot say; `None` otherwise.
    #[must_use]
    pub fn custom_start(&self) -> Option<&str> {
        self.custom.as_deref()
    }

    /// The left button up: a held ball is let go, and the swing runs from there.
    pub fn release(&mut self) {
        if self.dragging.take().is_some() {
            self.world.set_running(true);
            self.restart_clock();
        }
    }
}
