//! Screen tiles for primary rays: each tile lists only the objects whose projected
//! bounds can cover it. A primary ray through the tile can hit nothing else, so
//! testing the list gives the same nearest hit as testing everything (the lists keep
//! the query order, so ties resolve the same way too).

use super::camera::CameraRays;
use super::prepared::Prepared;
use glam::Vec3;

/// Tile edge in pixels.
pub const TILE: u32 = 16;

/// Primary-ray candidates per tile.
#[derive(Debug, Clone)]
pub struct Tiles {
    across: u32,
    lists: Vec<Vec<usize>>,
}

/// Pixel-space bounds of a box, or `None` when a corner is not in front of the eye
/// (then the box may cover any pixel).
fn screen_bounds(cam: &CameraRays, min: Vec3, max: Vec3) -> Option<(f32, f32, f32, f32)> {
    let mut b = (
        f32::INFINITY,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NEG_INFINITY,
    );
    for i in 0..8 {
        let corner = Vec3::new(
            if i & 1 == 0 { min.x } else { max.x },
            if i & 2 == 0 { min.y } else { max.y },
            if i & 4 == 0 { min.z } else { max.z },
        );
        let (x, y) = cam.project(corner)?;
        b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
    }
    Some(b)
}

impl Tiles {
    /// Candidate lists for a `width` x `height` picture.
    #[must_use]
    pub fn new(p: &Prepared<'_>, cam: &CameraRays, width: u32, height: u32) -> Self {
        let across = width.div_ceil(TILE);
        let down = height.div_ceil(TILE);
        let mut lists = vec![Vec::new(); (across * down) as usize];
        for (i, bounds) in p.in_query_order() {
            // Planes (no bounds) and boxes reaching behind the eye go everywhere.
            let (x0, y0, x1, y1) = match bounds.and_then(|b| screen_bounds(cam, b.min, b.max)) {
                // One pixel of margin covers round-off in the projection and the
                // sub-pixel sample offsets.
                Some((a, b, c, d)) => (a - 1.0, b - 1.0, c + 1.0, d + 1.0),
                None => (
                    f32::NEG_INFINITY,
                    f32::NEG_INFINITY,
                    f32::INFINITY,
                    f32::INFINITY,
                ),
            };
            if x1 < 0.0 || y1 < 0.0 || x0 > width as f32 || y0 > height as f32 {
                continue;
            }
            let tx = |x: f32| ((x.max(0.0) / TILE as f32) as u32).min(across - 1);
            let ty = |y: f32| ((y.max(0.0) / TILE as f32) as u32).min(down - 1);
            for row in ty(y0)..=ty(y1) {
                for col in tx(x0)..=tx(x1) {
                    lists[(row * across + col) as usize].push(i);
                }
            }
        }
        Self { across, lists }
    }

    /// The candidates of pixel `(x, y)`.
    #[must_use]
    pub fn at(&self, x: u32, y: u32) -> &[usize] {
        &self.lists[((y / TILE) * self.across + x / TILE) as usize]
    }
}
