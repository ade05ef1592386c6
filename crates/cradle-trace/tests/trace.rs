//! The tracer from first principles: intersections, shading and small pictures.
//! Whole frames of the cradle are in `frames.rs`.

use cradle_trace::geometry::{Ray, hit_cylinder, hit_plane, hit_sphere};
use cradle_trace::reference::trace;
use cradle_trace::{self as trace, Camera, Light, Material, Object, Prepared, Scene, Shape};
use glam::Vec3;

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
        coarse: 1,
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
    trace(&p, r)
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

#[test]
fn floor_i64_is_floor_as_i64_for_every_kind_of_value() {
    use cradle_trace::geometry::floor_i64;
    let mut values = vec![
        0.0,
        -0.0,
        0.5,
        -0.5,
        1.0,
        -1.0,
        -1.000_000_1,
        8_388_607.5,
        -8_388_607.5,
        8_388_608.0,
        -8_388_609.0,
        1e18,
        -1e18,
        9.3e18,
        -9.3e18,
        9.223_372e18,
        f32::MAX,
        f32::MIN,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ];
    // A sweep over the checker's range: floor positions / square sizes.
    values.extend((-20_000..20_000).map(|i| i as f32 * 0.013_7));
    for v in values {
        assert_eq!(floor_i64(v), v.floor() as i64, "{v}");
    }
}

#[test]
fn a_counted_render_is_the_same_picture_and_counts_every_row_of_each_pass() {
    use std::sync::atomic::{AtomicU32, Ordering};
    let object = |shape| Object {
        shape,
        material: Material {
            color: Vec3::splat(0.6),
            specular: Some(50.0),
            reflective: 0.5,
            checker: None,
        },
        moving: false,
    };
    let mut scene = Scene {
        objects: vec![
            object(Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            }),
            object(Shape::Sphere {
                centre: Vec3::new(0.0, 0.1, 0.0),
                radius: 0.05,
            }),
        ],
        lights: vec![Light::Point {
            position: Vec3::new(0.3, 1.0, 0.5),
            color: Vec3::ONE,
        }],
        camera: Camera {
            position: Vec3::new(0.0, 0.2, 0.5),
            look_at: Vec3::new(0.0, 0.1, 0.0),
            fov_deg: 40.0,
        },
        size: (48, 24),
        ..Scene::default()
    };
    // One pass without anti-aliasing; two (centres, then edges) with it.
    for (samples, adaptive, passes) in [(1, None, 1), (4, Some(0.1), 2)] {
        scene.samples = samples;
        scene.adaptive = adaptive;
        let done = AtomicU32::new(0);
        let counted = trace::render_counting(&scene, &done);
        assert!(counted.rgba == trace::render(&scene).rgba, "the same bytes");
        assert_eq!(done.load(Ordering::Relaxed), passes * 24);
    }
}

/// A coarse frame (one ray per 2x2 block, `Scene::coarse`) is the picture
/// traced at half the size, stretched: its pixel at the centre of a block of
/// a flat region is that region's colour, it stays close to the full frame
/// (a moving view's preview), and an incremental renderer's next frame at
/// full detail is the full render, byte for byte.
#[test]
fn a_coarse_frame_previews_the_picture_and_the_next_frame_is_full() {
    let light = Light::Point {
        position: Vec3::new(2., 3., 4.),
        color: Vec3::ONE,
    };
    let mut s = scene(
        vec![sphere(Vec3::ZERO, 1.0, matte(Vec3::new(0.8, 0.3, 0.2)))],
        vec![light],
        (64, 48),
    );
    let full = cradle_trace::render(&s);
    s.coarse = 2;
    let coarse = cradle_trace::render(&s);
    assert_eq!((coarse.width, coarse.height), (64, 48));
    assert_ne!(coarse.rgba, full.rgba, "a preview, not the picture");
    // The background far from the sphere is flat: equal there.
    assert_eq!(coarse.rgba[..16], full.rgba[..16]);
    // On average close: under 8 levels of 255 per byte.
    let diff: u64 = coarse
        .rgba
        .iter()
        .zip(&full.rgba)
        .map(|(&a, &b)| u64::from(a.abs_diff(b)))
        .sum();
    assert!(diff < 8 * full.rgba.len() as u64, "mean difference {diff}");
    let mut inc = cradle_trace::Incremental::new();
    inc.render(&s);
    assert_eq!(inc.image().map(|i| &i.rgba), Some(&coarse.rgba));
    s.coarse = 1;
    let next = inc.render(&s).clone();
    assert!(inc.last_was_full());
    assert!(next.rgba == full.rgba, "at rest, the full frame");
}
