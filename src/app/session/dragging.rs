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
            self.retrace = true;
        }
        true
    }

    /// The left button up: a held ball is let go, and the swing runs from there.
    pub fn release(&mut self) {
        if self.dragging.take().is_some() {
            self.world.set_running(true);
            self.restart_clock();
        }
    }
}
