//! The tracer from first principles: intersections, shading, pictures, and the
//! parallel render against the serial one.

use glam::Vec3;
use newtons_cradle::config::Config;
use newtons_cradle::scene::CradleWorld;
use newtons_cradle::trace::geometry::{Ray, hit_cylinder, hit_plane, hit_sphere};
use newtons_cradle::trace::motion::Motion;
use newtons_cradle::trace::shade::{radiance_bound, trace};
use newtons_cradle::trace::{self, Camera, Light, Material, Object, Prepared, Scene, Shape};

/// f32 arithmetic on metre-sized numbers: a few ulps of 1 m.
const EPS: f32 = 1e-5;

fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
    Ray {
        origin: Vec3::from(o),
        dir: Vec3::from(d).normalize(),
    }
}

#[test]
fn sphere_from_outside_inside_tangent_and_miss() {
    let c = Vec3::ZERO;
    assert!(
        (hit_sphere(&ray([0., 0., 5.], [0., 0., -1.]), c, 1.0).expect("hit") - 4.0).abs() < EPS
    );
    assert!(
        (hit_sphere(&ray([0., 0., 0.], [0., 1., 0.]), c, 1.0).expect("inside") - 1.0).abs() < EPS
    );
    // Tangent: the ray touches the sphere at x = 1.
    let t = hit_sphere(&ray([1., 0., 5.], [0., 0., -1.]), c, 1.0).expect("tangent");
    assert!((t - 5.0).abs() < 1e-3);
    assert_eq!(
        hit_sphere(&ray([1.01, 0., 5.], [0., 0., -1.]), c, 1.0),
        None
    );
    assert_eq!(
        hit_sphere(&ray([0., 0., 5.], [0., 0., 1.]), c, 1.0),
        None,
        "sphere behind the ray"
    );
}

#[test]
fn cylinder_body_caps_parallel_through_axis_and_tilted() {
    let (a, b, r) = (Vec3::new(0., -1., 0.), Vec3::new(0., 1., 0.), 0.5);
    // Body, through the axis: t = distance - r, normal back towards the ray.
    let (t, n) = hit_cylinder(&ray([0., 0., 3.], [0., 0., -1.]), a, b, r).expect("body");
    assert!((t - 2.5).abs() < EPS && (n - Vec3::Z).length() < EPS);
    // Off-axis chord: x = 0.3 meets the body at z = sqrt(0.25 - 0.09) = 0.4.
    let (t, _) = hit_cylinder(&ray([0.3, 0., 3.], [0., 0., -1.]), a, b, r).expect("chord");
    assert!((t - 2.6).abs() < EPS);
    // Beyond the ends: miss.
    assert!(hit_cylinder(&ray([0., 1.2, 3.], [0., 0., -1.]), a, b, r).is_none());
    // Along the axis from above: the top cap, facing +y.
    let (t, n) = hit_cylinder(&ray([0.2, 4., 0.], [0., -1., 0.]), a, b, r).expect("cap");
    assert!((t - 3.0).abs() < EPS && (n - Vec3::Y).length() < EPS);
    // Parallel to the axis outside the radius: miss.
    assert!(hit_cylinder(&ray([0.6, 4., 0.], [0., -1., 0.]), a, b, r).is_none());
    // From inside, along the axis: the far cap.
    let (t, _) = hit_cylinder(&ray([0., 0., 0.], [0., -1., 0.]), a, b, r).expect("inside");
    assert!((t - 1.0).abs() < EPS);
    // Tilted axis (1, 1, 0): a ray perpendicular to it through (0.5, 0.5, 0).
    let (a, b) = (Vec3::ZERO, Vec3::new(1., 1., 0.));
    let (t, n) = hit_cylinder(&ray([0.5, 0.5, 5.], [0., 0., -1.]), a, b, 0.1).expect("tilted");
    assert!((t - 4.9).abs() < EPS && (n - Vec3::Z).length() < EPS);
    assert!(
        hit_cylinder(&ray([1.2, 1.2, 5.], [0., 0., -1.]), a, b, 0.1).is_none(),
        "past the tilted end"
    );
}

#[test]
fn plane_from_both_sides_and_parallel() {
    let (p, n) = (Vec3::ZERO, Vec3::Y);
    assert!((hit_plane(&ray([0., 2., 0.], [0., -1., 0.]), p, n).expect("above") - 2.0).abs() < EPS);
    assert!((hit_plane(&ray([0., -3., 0.], [0., 1., 0.]), p, n).expect("below") - 3.0).abs() < EPS);
    assert_eq!(hit_plane(&ray([0., 1., 0.], [1., 0., 0.]), p, n), None);
    assert_eq!(
        hit_plane(&ray([0., 1., 0.], [0., 1., 0.]), p, n),
        None,
        "plane behind"
    );
}

fn matte(color: Vec3) -> Material {
    Material {
        color,
        specular: None,
        reflective: 0.0,
        checker: None,
    }
}

fn scene(objects: Vec<Object>, lights: Vec<Light>, size: (u32, u32)) -> Scene {
    Scene {
        objects,
        lights,
        camera: Camera {
            position: Vec3::new(0., 0., 5.),
            look_at: Vec3::ZERO,
            fov_deg: 30.0,
        },
        background: Vec3::new(0.1, 0.2, 0.3),
        size,
        max_depth: 3,
        samples: 1,
        adaptive: None,
        motion_bounds: None,
    }
}

fn sphere(centre: Vec3, radius: f32, material: Material) -> Object {
    Object {
        shape: Shape::Sphere { centre, radius },
        material,
        moving: false,
    }
}

fn radiance(s: &Scene, r: &Ray) -> Vec3 {
    let p = Prepared::new(s);
    trace(&p, r, 0, 1.0, radiance_bound(&p), &mut Motion::new(None))
}

#[test]
fn a_point_facing_the_light_is_brighter_than_one_turned_away() {
    let s = scene(
        vec![sphere(Vec3::ZERO, 1.0, matte(Vec3::ONE))],
        vec![
            Light::Ambient {
                color: Vec3::splat(0.1),
            },
            Light::Point {
                position: Vec3::new(5., 0., 0.),
                color: Vec3::ONE,
            },
        ],
        (8, 8),
    );
    let lit = radiance(&s, &ray([0.5, 0., 5.], [0., 0., -1.]));
    let dark = radiance(&s, &ray([-0.5, 0., 5.], [0., 0., -1.]));
    assert!(lit.x > dark.x);
    // Turned away from the light, only the ambient term remains: base * 0.1.
    assert!((dark - Vec3::splat(0.1)).length() < 1e-6, "{dark}");
    // Facing: ambient + Lambert cos(angle); the hit is at (0.5, 0, sqrt(0.75)).
    let want = 0.1
        + Vec3::new(0.5, 0., 0.75f32.sqrt())
            .dot((Vec3::new(5., 0., 0.) - Vec3::new(0.5, 0., 0.75f32.sqrt())).normalize());
    assert!((lit.x - want).abs() < 1e-5, "{} vs {want}", lit.x);
}

#[test]
fn a_point_behind_an_occluder_is_in_shadow() {
    let floor = Object {
        shape: Shape::Plane {
            point: Vec3::new(0., -1., 0.),
            normal: Vec3::Y,
        },
        material: matte(Vec3::splat(0.8)),
        moving: false,
    };
    let blocker = sphere(Vec3::new(0., 1., 0.), 0.5, matte(Vec3::ONE));
    let s = scene(
        vec![floor, blocker],
        vec![
            Light::Ambient {
                color: Vec3::splat(0.2),
            },
            Light::Point {
                position: Vec3::new(0., 4., 0.),
                color: Vec3::ONE,
            },
        ],
        (8, 8),
    );
    // Straight down onto the floor under the blocker, and far to the side of it.
    let shadowed = radiance(&s, &ray([0., -0.5, 0.], [0., -1., 0.]));
    let open = radiance(&s, &ray([3., -0.5, 0.], [0., -1., 0.]));
    assert!(
        (shadowed - Vec3::splat(0.8 * 0.2)).length() < 1e-6,
        "only ambient: {shadowed}"
    );
    assert!(open.x > shadowed.x + 0.1);
}

#[test]
fn reflective_one_is_a_mirror_and_zero_is_not() {
    let mut mirror = matte(Vec3::new(1., 0., 0.));
    mirror.reflective = 1.0;
    let lights = vec![Light::Ambient {
        color: Vec3::splat(0.5),
    }];
    // The ray hits the sphere's front at normal incidence and comes straight back to
    // the empty sky behind the camera: the background.
    let r = ray([0., 0., 5.], [0., 0., -1.]);
    let s = scene(
        vec![sphere(Vec3::ZERO, 1.0, mirror)],
        lights.clone(),
        (8, 8),
    );
    assert_eq!(radiance(&s, &r), s.background);
    let s = scene(
        vec![sphere(Vec3::ZERO, 1.0, matte(Vec3::new(1., 0., 0.)))],
        lights,
        (8, 8),
    );
    assert_eq!(radiance(&s, &r), Vec3::new(0.5, 0., 0.));
}

#[test]
fn a_lone_sphere_covers_its_projected_disc() {
    let (w, h) = (200u32, 200u32);
    let s = scene(
        vec![sphere(Vec3::ZERO, 1.0, matte(Vec3::ONE))],
        vec![Light::Ambient { color: Vec3::ONE }],
        (w, h),
    );
    let img = trace::render_serial(&s);
    let bg = [trace::srgb8(0.1), trace::srgb8(0.2), trace::srgb8(0.3)];
    let covered = img.rgba.chunks_exact(4).filter(|p| p[..3] != bg).count() as f64;
    // Silhouette: a circle of angular radius asin(R/D) about the axis; on the image
    // plane at distance 1 its radius is R / sqrt(D^2 - R^2), in pixels times
    // (h/2) / tan(fov/2).
    let px = 1.0 / (24f64).sqrt() * (f64::from(h) / 2.0) / (15f64.to_radians()).tan();
    let area = std::f64::consts::PI * px * px;
    // Pixel-centre sampling errs by at most the pixels the rim crosses, and in
    // practice by far less: 1% of the area (the rim is 2 pi r ~ 4% of it).
    assert!(
        (covered - area).abs() < 0.01 * area,
        "covered {covered}, disc {area}"
    );
}

#[test]
fn a_symmetric_scene_gives_a_mirror_symmetric_picture() {
    let s = scene(
        vec![
            sphere(
                Vec3::new(-1.2, 0., 0.),
                0.8,
                matte(Vec3::new(0.9, 0.2, 0.2)),
            ),
            sphere(Vec3::new(1.2, 0., 0.), 0.8, matte(Vec3::new(0.9, 0.2, 0.2))),
            Object {
                shape: Shape::Plane {
                    point: Vec3::new(0., -0.8, 0.),
                    normal: Vec3::Y,
                },
                material: matte(Vec3::splat(0.5)),
                moving: false,
            },
        ],
        vec![
            Light::Ambient {
                color: Vec3::splat(0.1),
            },
            Light::Point {
                position: Vec3::new(0., 3., 3.),
                color: Vec3::ONE,
            },
        ],
        (120, 60),
    );
    let img = trace::render_serial(&s);
    let (w, h) = (img.width as usize, img.height as usize);
    let mut differ = 0;
    for y in 0..h {
        for x in 0..w / 2 {
            let (l, r) = ((y * w + x) * 4, (y * w + (w - 1 - x)) * 4);
            for c in 0..3 {
                let d = (i32::from(img.rgba[l + c]) - i32::from(img.rgba[r + c])).abs();
                // Mirrored rays differ by an ulp of f32, which can move a value across
                // a rounding boundary: one 8-bit step, rarely.
                assert!(d <= 1, "pixel ({x}, {y}) channel {c}: {d}");
                differ += usize::from(d > 0);
            }
        }
    }
    assert!(differ < w * h / 100, "{differ} channels off by one");
}

fn cradle_scene(width: u32, height: u32, t: f64) -> Scene {
    let mut config = Config::default();
    config.render.width = width;
    config.render.height = height;
    config.start.lift = 2;
    let mut world = CradleWorld::new(&config);
    world.show_at(t);
    world.scene().clone()
}

#[test]
fn parallel_render_equals_serial_byte_for_byte() {
    let s = cradle_scene(240, 120, 0.37);
    let serial = trace::render_serial(&s);
    for threads in [1, 2, 3, 7] {
        let pool = trace::pool(threads).expect("pool");
        let parallel = pool.install(|| trace::render(&s));
        assert!(
            parallel == serial,
            "{threads} threads differ from the serial render"
        );
    }
}

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
    use newtons_cradle::scene::view::{fitted_camera, frame_corners};
    // The default camera sees the default cradle as configured; with more balls
    // `camera.fit` moves it back until the frame is in view again.
    let default = Config::default();
    assert_eq!(fitted_camera(&default), default.camera);
    for balls in [5, 50, 200] {
        let mut config = Config::default();
        config.cradle.balls = balls;
        let cam = fitted_camera(&config);
        for corner in frame_corners(&config) {
            let (sx, sy, depth) =
                view_coords(&cam, config.render.width, config.render.height, corner);
            assert!(
                depth > 0.0 && sx.abs() < 1.0 && sy.abs() < 1.0,
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

#[test]
fn srgb_bytes_round_the_standard_curve_to_nearest() {
    use newtons_cradle::trace::srgb8;
    // Against the IEC 61966-2-1 formula evaluated in f64, away from the decision
    // points (a value within 1e-6 of one may round either way in f32).
    for i in 0..=10_000 {
        let x = f64::from(i) / 10_000.0;
        let s = if x <= 0.003_130_8 {
            12.92 * x
        } else {
            1.055 * x.powf(1.0 / 2.4) - 0.055
        };
        let exact = s * 255.0;
        if (exact - exact.floor() - 0.5).abs() < 1e-3 {
            continue;
        }
        assert_eq!(srgb8(x as f32), exact.round() as u8, "linear {x}");
    }
    assert_eq!(
        (
            srgb8(-1.0),
            srgb8(0.0),
            srgb8(1.0),
            srgb8(7.0),
            srgb8(f32::NAN)
        ),
        (0, 0, 255, 255, 0)
    );
}

/// A default cradle at a small picture size with the given balls, lift and gap.
fn small_cradle(size: (u32, u32), balls: usize, lift: usize, gap: f64) -> Config {
    let mut config = Config::default();
    (config.render.width, config.render.height) = size;
    config.cradle.balls = balls;
    config.cradle.gap = gap;
    config.start.lift = lift;
    config
}

#[test]
fn tile_culling_and_the_bvh_leave_every_byte_as_the_full_render_makes_it() {
    use newtons_cradle::trace::{RenderOptions, render_serial_with};
    // Swinging cradles of several sizes and lifts, at times spread over a swing,
    // and a camera close enough that shapes reach past the picture's edges.
    for (balls, lift, gap, t) in [
        (5, 1, 0.0, 0.0),
        (5, 2, 0.0, 0.37),
        (9, 3, 0.002, 0.8),
        (20, 3, 0.001, 1.3),
        (60, 5, 0.0, 0.6),
        (200, 12, 0.0, 0.9),
    ] {
        let mut world = CradleWorld::new(&small_cradle((300, 150), balls, lift, gap));
        world.show_at(t);
        let mut s = world.scene().clone();
        let full = render_serial_with(&s, RenderOptions::FULL);
        assert!(
            render_serial_with(&s, RenderOptions::FAST) == full,
            "{balls} balls at t = {t}"
        );
        s.camera.position = Vec3::new(0.05, 0.16, 0.12);
        let full = render_serial_with(&s, RenderOptions::FULL);
        assert!(
            render_serial_with(&s, RenderOptions::FAST) == full,
            "{balls} balls at t = {t}, close up"
        );
    }
}

#[test]
fn incremental_frames_equal_full_renders_over_300_frames_of_a_swing() {
    use newtons_cradle::trace::{Incremental, RenderOptions, render_serial_with};
    for (balls, lift, gap) in [(5, 1, 0.0), (5, 2, 0.0), (20, 3, 0.0), (5, 1, 0.002)] {
        let mut world = CradleWorld::new(&small_cradle((160, 80), balls, lift, gap));
        let mut inc = Incremental::new();
        for n in 0..300 {
            world.show_at(f64::from(n) / 60.0);
            let scene = world.scene();
            let full = render_serial_with(scene, RenderOptions::FULL);
            let frame = inc.render(scene);
            assert!(
                *frame == full,
                "{balls} balls, {lift} lifted, gap {gap}: frame {n} differs"
            );
            assert_eq!(
                inc.last_was_full(),
                n == 0,
                "only the first frame is traced in full"
            );
        }
        let share = inc.dynamic_share();
        assert!(
            share > 0.0 && share < 0.9,
            "{balls} balls: re-traces {share:.2} of the pixels"
        );
    }
}

#[test]
fn incremental_renders_in_full_when_anything_static_changes() {
    use newtons_cradle::trace::Incremental;
    let mut world = CradleWorld::new(&Config::default());
    world.show_at(0.2);
    let mut s = world.scene().clone();
    let mut inc = Incremental::new();
    let _ = inc.render(&s);
    let _ = inc.render(&s);
    assert!(!inc.last_was_full());
    s.camera.fov_deg += 1.0;
    let _ = inc.render(&s);
    assert!(inc.last_was_full(), "a new camera");
    s.lights.pop();
    let _ = inc.render(&s);
    assert!(inc.last_was_full(), "a light less");
    s.motion_bounds = None;
    let _ = inc.render(&s);
    let _ = inc.render(&s);
    assert!(inc.last_was_full(), "no motion box: nothing can be reused");
}

/// PSNR (dB) of `img` against `reference`, over the RGB bytes.
fn psnr(img: &trace::Image, reference: &trace::Image) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0);
    for (i, (a, b)) in img.rgba.iter().zip(&reference.rgba).enumerate() {
        if i % 4 != 3 {
            let d = f64::from(*a) - f64::from(*b);
            sum += d * d;
            n += 1.0;
        }
    }
    10.0 * (255.0 * 255.0 / (sum / n)).log10()
}

#[test]
fn adaptive_anti_aliasing_supersamples_exactly_the_edges() {
    let mut s = cradle_scene(240, 120, 0.4);
    s.samples = 8;
    let uniform = trace::render_serial(&s);
    s.samples = 1;
    let single = trace::render_serial(&s);
    s.samples = 8;
    s.adaptive = Some(0.05);
    let adaptive = trace::render_serial(&s);
    // Edge pixels (in the one-sample picture) carry the 8-sample colour, the
    // others the one-sample colour, byte for byte.
    let (w, h) = (240usize, 120usize);
    let px = |img: &trace::Image, x: usize, y: usize| {
        img.rgba[(y * w + x) * 4..(y * w + x) * 4 + 3].to_vec()
    };
    let mut edges = 0;
    for y in 0..h {
        for x in 0..w {
            let here = px(&single, x, y);
            let near = [
                (x.wrapping_sub(1), y),
                (x + 1, y),
                (x, y.wrapping_sub(1)),
                (x, y + 1),
            ];
            let edge = near
                .iter()
                .filter(|(nx, ny)| *nx < w && *ny < h)
                .any(|&(nx, ny)| {
                    here.iter()
                        .zip(px(&single, nx, ny))
                        .any(|(a, b)| f32::from(a.abs_diff(b)) > 0.05 * 255.0)
                });
            let want = if edge { px(&uniform, x, y) } else { here };
            assert_eq!(px(&adaptive, x, y), want, "pixel ({x}, {y}), edge {edge}");
            edges += usize::from(edge);
        }
    }
    // A cradle has edges, but they are a minority of the picture.
    assert!(edges > 100 && edges < w * h / 2, "{edges} edge pixels");
    // And it is closer to a 16-sample reference than one sample is.
    s.adaptive = None;
    s.samples = 16;
    let reference = trace::render_serial(&s);
    assert!(psnr(&adaptive, &reference) > psnr(&single, &reference) + 3.0);
}

#[test]
fn adaptive_parallel_and_incremental_equal_serial() {
    let config = {
        let mut c = small_cradle((160, 80), 5, 1, 0.0);
        c.render.samples = 4;
        c.render.adaptive = true;
        c
    };
    let mut world = CradleWorld::new(&config);
    world.set_running(true);
    let mut inc = trace::Incremental::new();
    for threads in [1u32, 2, 3] {
        let pool = trace::pool(threads as usize).unwrap();
        for f in 0..4 {
            world.show_at(0.3 + f64::from(f) / 30.0 + f64::from(threads));
            let serial = trace::render_serial_with(world.scene(), trace::RenderOptions::FULL);
            assert_eq!(pool.install(|| trace::render(world.scene())), serial);
            assert_eq!(pool.install(|| inc.render(world.scene()).clone()), serial);
        }
    }
}

#[test]
fn shadow_culling_leaves_every_byte_as_the_full_render_makes_it() {
    use newtons_cradle::trace::{RenderOptions, render_serial_with};
    // Lights high and low (one below the rails, so the frame's shadow reaches
    // every point of the floor), beside the cradle, straight above, and
    // directional; each picture equals the reference with every shadow ray
    // testing every object.
    let mut world = CradleWorld::new(&small_cradle((240, 120), 7, 2, 0.0));
    world.show_at(0.45);
    let base = world.scene().clone();
    let white = Vec3::splat(0.6);
    let lights = [
        vec![Light::Point {
            position: Vec3::new(-0.6, 0.9, 0.8),
            color: white,
        }],
        vec![Light::Point {
            position: Vec3::new(0.3, 0.2, 0.1),
            color: white,
        }],
        vec![Light::Point {
            position: Vec3::new(0.0, 2.0, 0.0),
            color: white,
        }],
        vec![Light::Point {
            position: Vec3::new(1.5, 0.05, -0.4),
            color: white,
        }],
        vec![
            Light::Directional {
                direction: Vec3::new(0.3, -1.0, -0.2).normalize(),
                color: white,
            },
            Light::Ambient {
                color: Vec3::splat(0.1),
            },
        ],
    ];
    for set in lights {
        let s = Scene {
            lights: set.clone(),
            ..base.clone()
        };
        assert!(
            render_serial_with(&s, RenderOptions::FAST)
                == render_serial_with(&s, RenderOptions::FULL),
            "lights {set:?}"
        );
    }
}
