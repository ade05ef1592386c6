//! The view: the default camera sees the whole cradle, `camera.fit` moves it back
//! for more balls, and a long row is seen along its length, each checked with an
//! f64 projection of the test's own.

use newtons_cradle::config::Config;

/// Where `point` lands in the view of `cam` for a `width x height` picture, as
/// `(x, y)` in -1..=1 across the picture, and its depth along the line of sight:
/// an f64 projection of our own, independent of the tracer's.
fn view_coords(
    cam: &newtons_cradle::config::CameraConfig,
    width: u32,
    height: u32,
    point: glam::DVec3,
) -> (f64, f64, f64) {
    use glam::DVec3;
    let eye = DVec3::from(cam.position);
    let fwd = (DVec3::from(cam.look_at) - eye).normalize();
    let right = fwd.cross(DVec3::Y).normalize();
    let up = right.cross(fwd);
    let half_h = (cam.fov_deg.to_radians() / 2.0).tan();
    let half_w = half_h * f64::from(width) / f64::from(height);
    let v = point - eye;
    let depth = v.dot(fwd);
    (
        v.dot(right) / depth / half_w,
        v.dot(up) / depth / half_h,
        depth,
    )
}

#[test]
fn the_whole_cradle_is_in_view_at_the_default_camera() {
    use newtons_cradle::scene::fit::fitted_camera;
    use newtons_cradle::scene::view::frame_corners;
    // The default camera sees the default cradle as configured; with more balls
    // `camera.fit` moves it back until the frame is in view again.
    let default = Config::default();
    assert_eq!(fitted_camera(&default), default.camera);
    for balls in [5, 12, 20] {
        let mut config = Config::default();
        config.cradle.balls = balls;
        let cam = fitted_camera(&config);
        for corner in frame_corners(&config) {
            let (sx, sy, depth) =
                view_coords(&cam, config.render.width, config.render.height, corner);
            assert!(
                depth > 0.0 && sx.abs() < 1.0 && in_band(sy),
                "{balls} balls: frame corner {corner:?} at ({sx:.3}, {sy:.3})"
            );
        }
        // Moved back along its line of sight only: the same view direction.
        let dir = |c: &newtons_cradle::config::CameraConfig| {
            (glam::DVec3::from(c.look_at) - glam::DVec3::from(c.position)).normalize()
        };
        assert!((dir(&cam) - dir(&default.camera)).length() < 1e-12);
    }
}

/// Whether a height `sy` (-1 at the bottom edge, 1 at the top) lies between
/// the window's status band (the top 12%) and its help band (the bottom 12%).
fn in_band(sy: f64) -> bool {
    sy.abs() <= 0.76
}

#[test]
fn the_whole_swing_stays_in_view_at_lift_angles_over_90_degrees() {
    use newtons_cradle::scene::fit::fitted_camera;
    // Balls swung to 120, 150 and 179 degrees rise above the rails; the
    // fitted view keeps each ball's whole swing (both sides, up to the lift
    // angle) clear of the window's status and help bands.
    for angle in [60.0, 120.0, 150.0, 179.0] {
        for lift in [1, 2, 5] {
            let mut config = Config::default();
            config.start.lift = lift;
            config.start.angle_deg = angle;
            let cam = fitted_camera(&config);
            let c = &config.cradle;
            let (w, h) = (config.render.width, config.render.height);
            let first = -0.5 * (c.balls as f64 - 1.0) * 2.0 * c.radius;
            for i in [0, c.balls - 1] {
                let pivot =
                    glam::DVec3::new(first + i as f64 * 2.0 * c.radius, c.pivot_height, 0.0);
                for k in 0..=36 {
                    let theta = (f64::from(k) / 18.0 - 1.0) * angle.to_radians();
                    let centre =
                        pivot + c.length * glam::DVec3::new(theta.sin(), -theta.cos(), 0.0);
                    for edge in [
                        glam::DVec3::Y,
                        -glam::DVec3::Y,
                        glam::DVec3::X,
                        -glam::DVec3::X,
                    ] {
                        let (sx, sy, depth) = view_coords(&cam, w, h, centre + edge * c.radius);
                        assert!(
                            depth > 0.0 && sx.abs() < 0.95 && in_band(sy),
                            "lift {lift} at {angle}: ball {i} at {theta:.2} rad out at ({sx:.3}, {sy:.3})"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn a_long_row_is_seen_along_its_length_with_every_ball_in_view_and_larger() {
    use newtons_cradle::scene::fit::fitted_camera;
    // Head-on, the frame (longer than the row of balls) fits in 95% of the
    // picture's width at best, so a ball is at most 0.95 * width / balls pixels
    // across. Along the row the median ball must be at least 1.3 times that
    // (the view is taken only when it gains 1.5 times over the real head-on
    // fit, which is smaller than this bound by the frame's room beyond the end
    // balls), and every ball and its pivot stay in the picture.
    for balls in [50, 100, 200] {
        let mut config = Config::default();
        config.cradle.balls = balls;
        let (w, h) = (config.render.width, config.render.height);
        let cam = fitted_camera(&config);
        let c = &config.cradle;
        let spacing = 2.0 * c.radius + c.gap;
        let first = -0.5 * (balls as f64 - 1.0) * spacing;
        let focal = 0.5 * f64::from(h) / (cam.fov_deg.to_radians() / 2.0).tan();
        let mut sizes = Vec::new();
        for i in 0..balls {
            let x = first + i as f64 * spacing;
            for y in [c.pivot_height - c.length, c.pivot_height] {
                let (sx, sy, depth) = view_coords(&cam, w, h, glam::DVec3::new(x, y, 0.0));
                assert!(
                    depth > 0.0 && sx.abs() < 1.0 && sy.abs() < 1.0,
                    "{balls} balls: ball {i} at height {y} is out of view at ({sx:.3}, {sy:.3})"
                );
                if y < c.pivot_height {
                    sizes.push(2.0 * c.radius * focal / depth);
                }
            }
        }
        sizes.sort_by(f64::total_cmp);
        let median = sizes[balls / 2];
        let head_on_at_most = 0.95 * f64::from(w) / balls as f64;
        assert!(
            median >= 1.3 * head_on_at_most,
            "{balls} balls: median ball {median:.1} px, head-on up to {head_on_at_most:.1} px"
        );
    }
}
