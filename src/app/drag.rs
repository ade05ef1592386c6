//! Dragging a ball: the pixel's ray picks the ball with the tracer's own sphere
//! test; while dragged, the ray's meeting with the swing plane sets the angle,
//! and the ball lifts with every ball between it and the end it is pulled
//! towards, as a real cradle forces. Window-free: pixels in, angles out.

use crate::config::{Config, MAX_ANGLE_DEG};
use crate::physics::Snapshot;
use crate::scene::layout::Layout;
use crate::trace::Camera;
use crate::trace::camera::CameraRays;
use crate::trace::geometry::hit_sphere;
use glam::DVec3;

/// The ball the ray through pixel `(x, y)` meets first, if any.
#[must_use]
pub fn pick(config: &Config, cam: &Camera, snap: &Snapshot, (x, y): (f64, f64)) -> Option<usize> {
    let rays = CameraRays::new(cam, config.render.width, config.render.height);
    let ray = rays.ray(x as f32, y as f32);
    let layout = Layout::new(config);
    let l = config.cradle.length;
    (0..snap.theta.len())
        .filter_map(|i| {
            let (s, c) = snap.theta[i].sin_cos();
            let centre = layout.pivot(i) + DVec3::new(l * s, -l * c, 0.0);
            hit_sphere(&ray, centre.as_vec3(), config.cradle.radius as f32).map(|t| (t, i))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, i)| i)
}

/// The angles with ball `ball` dragged to where the ray through pixel `(x, y)`
/// meets the swing plane (z = 0), and the count of balls lifted: pulled left
/// (negative angle), it lifts with every ball to its left; pulled right, with
/// every ball to its right. `None` when the ray runs along the plane.
#[must_use]
pub fn dragged(
    config: &Config,
    cam: &Camera,
    ball: usize,
    (x, y): (f64, f64),
) -> Option<(Vec<f64>, usize, f64)> {
    let rays = CameraRays::new(cam, config.render.width, config.render.height);
    let ray = rays.ray(x as f32, y as f32);
    let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
    if d.z.abs() < 1e-9 {
        return None;
    }
    let p = o + d * (-o.z / d.z);
    let pivot = Layout::new(config).pivot(ball);
    let max = MAX_ANGLE_DEG.to_radians();
    let theta = (p.x - pivot.x).atan2(pivot.y - p.y).clamp(-max, max);
    let n = config.cradle.balls;
    let lifted = if theta < 0.0 { 0..=ball } else { ball..=n - 1 };
    let count = lifted.clone().count();
    let angles = (0..n)
        .map(|i| if lifted.contains(&i) { theta } else { 0.0 })
        .collect();
    Some((angles, count, theta.abs()))
}

#[cfg(test)]
mod tests {
    use super::{dragged, pick};
    use crate::config::Config;
    use crate::scene::CradleWorld;
    use crate::scene::layout::Layout;
    use crate::trace::camera::CameraRays;
    use glam::DVec3;

    #[test]
    fn the_ball_under_the_cursor_is_picked_and_empty_floor_picks_none() {
        let config = Config::default();
        let mut world = CradleWorld::new(&config);
        world.show_at(0.0);
        let (cam, snap) = (world.scene().camera, world.cradle().snapshot.clone());
        let rays = CameraRays::new(&cam, config.render.width, config.render.height);
        let layout = Layout::new(&config);
        for i in 0..config.cradle.balls {
            let (s, c) = snap.theta[i].sin_cos();
            let centre = layout.pivot(i) + DVec3::new(0.16 * s, -0.16 * c, 0.0);
            let (x, y) = rays.project(centre.as_vec3()).expect("in view");
            assert_eq!(
                pick(&config, &cam, &snap, (f64::from(x), f64::from(y))),
                Some(i)
            );
        }
        assert_eq!(
            pick(&config, &cam, &snap, (5.0, 590.0)),
            None,
            "a floor corner"
        );
    }

    #[test]
    fn pulling_right_lifts_the_ball_and_those_to_its_right_only() {
        let config = Config::default();
        let world = CradleWorld::new(&config);
        let cam = world.scene().camera;
        let rays = CameraRays::new(&cam, config.render.width, config.render.height);
        // A point of the swing plane up and to the right of the last pivot.
        let last = Layout::new(&config).pivot(4);
        let target = last + DVec3::new(0.1, -0.1, 0.0);
        let (x, y) = rays.project(target.as_vec3()).expect("in view");
        let (theta, lifted, angle) =
            dragged(&config, &cam, 3, (f64::from(x), f64::from(y))).expect("meets the plane");
        assert_eq!(lifted, 2, "balls 3 and 4");
        assert!(theta[3] > 0.0 && theta[3] == theta[4] && theta[..3].iter().all(|&t| t == 0.0));
        // Ball 3's pivot, one spacing (0.04 m) left of ball 4's, sees the point at
        // atan2(0.14, 0.1); the f32 ray through the projected pixel rounds by
        // far less than 1e-4 rad.
        assert!((angle - 0.14_f64.atan2(0.1)).abs() < 1e-4, "{angle}");
    }
}
