//! Where the cradle stands in the world, from the config: its pivots and the
//! frame's length. Spawning, the view and the long row's camera place things by
//! it.

use crate::config::Config;
use glam::DVec3;

/// The cradle's layout in world space, derived from the config.
#[derive(Debug, Clone, Copy)]
pub struct Layout {
    /// Pivot (swing axis point at z = 0) of ball 0 (m).
    pub first_pivot: DVec3,
    /// Distance between pivots (m).
    pub spacing: f64,
    /// Half the frame's length along x (m): the posts stand at x = +-this.
    pub half_width: f64,
}

impl Layout {
    /// The layout for `config`: pivots centred on x = 0, posts beyond any ball's reach.
    #[must_use]
    pub fn new(config: &Config) -> Self {
        let c = &config.cradle;
        let spacing = 2.0 * c.radius + c.gap;
        let first_x = -0.5 * (c.balls as f64 - 1.0) * spacing;
        // A ball lifted to `angle` swings no further out than that; beyond 90
        // degrees its centre reaches a full length sideways.
        let angle = config.lift_angle().min(std::f64::consts::FRAC_PI_2);
        let reach = c.length * angle.sin();
        Self {
            first_pivot: DVec3::new(first_x, c.pivot_height, 0.0),
            spacing,
            half_width: -first_x + reach + c.radius + c.frame_radius + 0.25 * c.length,
        }
    }

    /// Pivot of ball `i`.
    #[must_use]
    pub fn pivot(&self, i: usize) -> DVec3 {
        self.first_pivot + DVec3::X * (i as f64 * self.spacing)
    }
}
