//! The default view of a long row, for [`super::fit::fitted_camera`]. Fitted
//! head-on, a row of many balls becomes a thin strip (200 balls: 6 pixels a
//! ball across a 1200-pixel picture). Looked at along its length from the lifted
//! (left) end, the near balls are large and every ball is still in view, as in a
//! photograph of a long cradle. The view is picked from a fixed set of
//! candidates by the median ball's size in the picture; it is used only when
//! that beats the head-on fit by half again.

use super::layout::Layout;
use super::view::{camera, fit_region, motion_bounds};
use crate::config::{CameraConfig, Config};
use crate::trace::camera::CameraRays;
use glam::DVec3;

/// The oblique view wins only when its median ball is this much larger.
const BETTER_BY: f64 = 1.5;

/// The view along the row for `config`, if it shows the balls clearly larger
/// than `head_on` (the head-on fitted camera) does.
#[must_use]
pub fn along_the_row(config: &Config, head_on: &CameraConfig) -> Option<CameraConfig> {
    let here = median_ball_px(config, head_on)?;
    let c = &config.cradle;
    let layout = Layout::new(config);
    let first = layout.pivot(0);
    let row = layout.pivot(c.balls - 1).x - first.x;
    if row <= 0.0 {
        return None;
    }
    let h = c.pivot_height;
    let mut best: Option<(f64, CameraConfig)> = None;
    // Behind the left end (share of the row), height and distance in front
    // (multiples of the rails' height), and the point looked at along the row.
    for back in [-0.1, 0.0, 0.05, 0.1, 0.2] {
        for up in [0.8, 1.2, 1.6, 2.4] {
            for out in [0.8, 1.2, 2.0, 3.2, 4.8, 8.0, 12.0] {
                for along in [0.1, 0.2, 0.3, 0.4, 0.5] {
                    let cam = CameraConfig {
                        position: [first.x - back * row, up * h, out * h],
                        look_at: [first.x + along * row, 0.4 * h, 0.0],
                        ..head_on.clone()
                    };
                    if let Some(px) = median_ball_px(config, &cam)
                        && best.as_ref().is_none_or(|(b, _)| px > *b)
                    {
                        best = Some((px, cam));
                    }
                }
            }
        }
    }
    best.filter(|(px, _)| *px >= BETTER_BY * here)
        .map(|(_, cam)| cam)
}

/// The median diameter (pixels) of the balls at rest as `cam` sees them, or
/// `None` when a ball at rest, its pivot, or the swing at either end leaves the
/// fit region ([`super::view::fit_region`]).
#[must_use]
pub fn median_ball_px(config: &Config, cam: &CameraConfig) -> Option<f64> {
    let c = &config.cradle;
    let (w, h) = (config.render.width, config.render.height);
    let rays = CameraRays::new(&camera(cam), w, h);
    let (lo, hi) = motion_bounds(config);
    let (at_least, at_most) = fit_region(w, h);
    let seen = |p: DVec3| {
        rays.project(p.as_vec3()).is_some_and(|(x, y)| {
            x >= at_least.x && x <= at_most.x && y >= at_least.y && y <= at_most.y
        })
    };
    let layout = Layout::new(config);
    let rest = |i: usize| layout.pivot(i) - DVec3::Y * c.length;
    let low = rest(0).y;
    let ends = [
        DVec3::new(f64::from(lo.x), low, 0.0),
        DVec3::new(f64::from(hi.x), low, 0.0),
        DVec3::new(f64::from(lo.x), f64::from(hi.y), 0.0),
        DVec3::new(f64::from(hi.x), f64::from(hi.y), 0.0),
    ];
    if !ends.into_iter().all(seen) {
        return None;
    }
    let eye = DVec3::from(cam.position);
    let forward = (DVec3::from(cam.look_at) - eye).normalize();
    let focal = 0.5 * f64::from(h) / (0.5 * cam.fov_deg.to_radians()).tan();
    let mut sizes = Vec::with_capacity(c.balls);
    for i in 0..c.balls {
        if !seen(rest(i)) || !seen(layout.pivot(i)) {
            return None;
        }
        let depth = (rest(i) - eye).dot(forward);
        sizes.push(2.0 * c.radius * focal / depth);
    }
    sizes.sort_by(f64::total_cmp);
    Some(sizes[sizes.len() / 2])
}
