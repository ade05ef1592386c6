//! Packets against the scalar path: in tracked frames they note the motion
//! cells and segments it notes, and they render its bytes where a mirror ball
//! is checkered, where a plane's own rays would meet it again, and past the
//! scan limit of the bounces' nearest hits.

use super::{Frame, RenderOptions, image};
use crate::motion::RowMotion;
use crate::motion::Seg;
use crate::scene::{Camera, Light, Material, Object, Scene, Shape};
use glam::Vec3;

/// The packets and culling (`RenderOptions::FAST`) render the reference's
/// bytes (`RenderOptions::FULL`) of `scene`.
fn assert_fast_is_full(scene: &Scene, what: &str) {
    let fast = image(&Frame::new(scene, RenderOptions::FAST, false), false).0;
    let full = image(&Frame::new(scene, RenderOptions::FULL, false), false).0;
    assert!(fast == full, "{what}");
}

#[test]
fn packets_note_the_same_motion_cells_as_the_scalar_path() {
    // A reflective, checkered floor, a moving mirror ball and a moving
    // rod over it, two point lights: packets take most of the floor, and
    // their shadow and mirror rays cross the motion box.
    let floor = Material {
        color: Vec3::new(0.3, 0.2, 0.1),
        specular: Some(20.0),
        reflective: 0.1,
        checker: Some((Vec3::new(0.2, 0.1, 0.1), 0.05)),
    };
    let steel = Material {
        color: Vec3::splat(0.5),
        specular: Some(100.0),
        reflective: 0.6,
        checker: None,
    };
    let objects = vec![
        Object {
            shape: Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            material: floor,
            moving: false,
        },
        Object {
            shape: Shape::Sphere {
                centre: Vec3::new(0.0, 0.1, 0.0),
                radius: 0.05,
            },
            material: steel,
            moving: true,
        },
        Object {
            shape: Shape::Cylinder {
                a: Vec3::new(-0.2, 0.2, 0.05),
                b: Vec3::new(0.2, 0.22, 0.05),
                radius: 0.01,
            },
            material: steel,
            moving: true,
        },
    ];
    let light = |x: f32, y: f32| Light::Point {
        position: Vec3::new(x, y, 0.6),
        color: Vec3::splat(0.7),
    };
    let scene = Scene {
        objects,
        lights: vec![light(-0.5, 0.8), light(0.6, 0.5)],
        camera: Camera {
            position: Vec3::new(0.0, 0.35, 0.7),
            look_at: Vec3::new(0.0, 0.1, 0.0),
            fov_deg: 40.0,
        },
        background: Vec3::new(0.05, 0.06, 0.08),
        size: (97, 61),
        max_depth: 3,
        samples: 1,
        adaptive: None,
        motion_bounds: Some((Vec3::new(-0.3, 0.0, -0.1), Vec3::new(0.3, 0.3, 0.1))),
        coarse: 1,
    };
    let (fast_img, fast_rows) = image(&Frame::new(&scene, RenderOptions::FAST, true), false);
    let (full_img, full_rows) = image(&Frame::new(&scene, RenderOptions::FULL, true), false);
    assert!(fast_img == full_img, "the same picture");
    let cells = |rows: &[RowMotion]| {
        rows.iter()
            .flat_map(|r| r.cells.clone())
            .collect::<Vec<_>>()
    };
    let (fast, full) = (cells(&fast_rows), cells(&full_rows));
    let differing = fast.iter().zip(&full).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "pixels whose motion cells differ");
    // Free segments (camera rays, and the floor's shadow and mirror rays) leave
    // no cells: those are the cells of the rays off the ball and the rod.
    assert!(
        full.iter().filter(|&&m| m != 0).count() > 200,
        "the motion box is seen"
    );
    // And the same segments, pixel by pixel (in any order).
    let key = |s: &Seg| [s.a.x, s.a.y, s.a.z, s.b.x, s.b.y, s.b.z].map(f32::to_bits);
    let mut segments = 0;
    for (a, b) in fast_rows.iter().zip(&full_rows) {
        assert!(a.tracked() && b.tracked());
        for k in 0..a.cells.len() {
            let sorted = |r: &RowMotion| {
                let mut v: Vec<_> = r.of(k).iter().map(key).collect();
                v.sort_unstable();
                v
            };
            assert_eq!(sorted(a), sorted(b), "pixel {k}: segments differ");
            segments += b.of(k).len();
        }
    }
    assert!(segments > 2000, "{segments} segments");
}

#[test]
fn packets_equal_the_reference_with_a_checkered_mirror_ball() {
    // A checkered mirror ball and a mirror rod on a checkered mirror floor, six
    // bounces deep: the lanes meet a checker off the floor, and the ball and the
    // rod in each other. (A second plane would leave every pixel to the scalar
    // path: packets need the floor to be the one plane in view.)
    let mirror = |color: Vec3, reflective: f32, checker: Option<(Vec3, f32)>| Material {
        color,
        specular: Some(30.0),
        reflective,
        checker,
    };
    let plane = |point: Vec3, normal: Vec3, m: Material| Object {
        shape: Shape::Plane { point, normal },
        material: m,
        moving: false,
    };
    let tiles = Some((Vec3::new(0.1, 0.1, 0.2), 0.05));
    let objects = vec![
        plane(Vec3::ZERO, Vec3::Y, mirror(Vec3::splat(0.4), 0.3, tiles)),
        Object {
            shape: Shape::Sphere {
                centre: Vec3::new(0.0, 0.1, 0.0),
                radius: 0.08,
            },
            material: mirror(Vec3::new(0.6, 0.3, 0.2), 0.6, tiles),
            moving: false,
        },
        Object {
            shape: Shape::Cylinder {
                a: Vec3::new(-0.3, 0.05, 0.1),
                b: Vec3::new(0.3, 0.07, 0.1),
                radius: 0.015,
            },
            material: mirror(Vec3::splat(0.5), 0.7, None),
            moving: false,
        },
    ];
    let scene = Scene {
        objects,
        lights: vec![
            Light::Ambient {
                color: Vec3::splat(0.1),
            },
            Light::Point {
                position: Vec3::new(-0.5, 0.8, 0.6),
                color: Vec3::splat(0.8),
            },
        ],
        camera: Camera {
            position: Vec3::new(0.1, 0.3, 0.8),
            look_at: Vec3::new(0.0, 0.1, 0.0),
            fov_deg: 45.0,
        },
        background: Vec3::new(0.05, 0.06, 0.08),
        size: (83, 47),
        max_depth: 6,
        samples: 1,
        adaptive: None,
        motion_bounds: None,
        coarse: 1,
    };
    assert_fast_is_full(&scene, "the same picture");
}

#[test]
fn no_renderer_tests_a_planes_own_rays() {
    // A tilted mirror floor seen along its length from close by: about 700 m
    // off, a point's rounding outgrows the 2e-5 m lift of its mirror ray,
    // which, tested against the floor, would meet it again 1 cm on (and see
    // the floor from below, not the sky). The packets' mirror rays, the
    // culled scalar path's and the reference's skip it alike. (Deeper bounces
    // keep the rule through `Bounce::from`; the floor's shadow rays here run
    // along the normal, clear of it.)
    let normal = Vec3::new(0.0, 1.0, 1.0).normalize();
    let floor = Material {
        color: Vec3::new(0.3, 0.2, 0.1),
        specular: Some(20.0),
        reflective: 0.3,
        checker: Some((Vec3::new(0.2, 0.1, 0.1), 0.05)),
    };
    let ball = Object {
        shape: Shape::Sphere {
            centre: normal * 0.3,
            radius: 0.1,
        },
        material: floor,
        moving: false,
    };
    let eye = normal * 0.5 + Vec3::new(0.0, 0.0, 2.0);
    // Along the floor, and a little down towards it.
    let along = (Vec3::NEG_Z - normal * normal.z * -1.0).normalize();
    let scene = Scene {
        objects: vec![
            Object {
                shape: Shape::Plane {
                    point: Vec3::ZERO,
                    normal,
                },
                material: floor,
                moving: false,
            },
            ball,
        ],
        // Lighting the far floor fully (a point light would graze it there).
        lights: vec![Light::Directional {
            direction: -normal,
            color: Vec3::ONE,
        }],
        camera: Camera {
            position: eye,
            look_at: eye + along - normal * 0.01,
            fov_deg: 8.0,
        },
        // A sky that a mirror ray meeting the floor again would not see.
        background: Vec3::new(0.3, 0.4, 0.6),
        size: (64, 48),
        max_depth: 2,
        samples: 1,
        ..Scene::default()
    };
    // The scene does what it should: some of the floor's mirror rays, tested
    // against the floor, meet it.
    let p = crate::Prepared::new(&scene);
    let cam = crate::camera::CameraRays::new(&scene.camera, 64, 48);
    let mut again = 0;
    for (x, y) in (0..48).flat_map(|y| (0..64).map(move |x| (x, y))) {
        let ray = cam.ray(x as f32 + 0.5, y as f32 + 0.5);
        let Some(hit) = p.closest(&ray, f32::INFINITY).filter(|h| h.object == 0) else {
            continue;
        };
        let start = ray.at(hit.t) + hit.normal * crate::geometry::SURFACE_OFFSET;
        let dir = ray.dir - 2.0 * ray.dir.dot(hit.normal) * hit.normal;
        let mirror = crate::geometry::Ray { origin: start, dir };
        again += usize::from(
            p.closest(&mirror, f32::INFINITY)
                .is_some_and(|h| h.object == 0),
        );
    }
    assert!(again > 0, "no mirror ray meets its own floor");
    assert_fast_is_full(&scene, "packets and culling keep the rule");
}

#[test]
fn packets_equal_the_reference_past_the_scan_limit() {
    // A mirror ball on a floor, and above the eye, out of view, 1,122 small
    // balls that it mirrors: past `SCAN_AT_MOST` bounded objects, each lane of
    // a bounce walks the hierarchy, and the shading tests the object met again
    // (`hit_normal`), not the scan's `t`.
    let ball = Material {
        color: Vec3::new(0.5, 0.5, 0.55),
        specular: Some(120.0),
        reflective: 0.6,
        checker: None,
    };
    let floor = Material {
        checker: Some((Vec3::new(0.2, 0.1, 0.1), 0.05)),
        reflective: 0.1,
        ..ball
    };
    let at = |centre: Vec3, radius: f32| Object {
        shape: Shape::Sphere { centre, radius },
        material: ball,
        moving: false,
    };
    let mut objects = vec![
        Object {
            shape: Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            material: floor,
            moving: false,
        },
        at(Vec3::new(0.0, 0.15, 0.0), 0.15),
    ];
    for (i, j) in (0..33).flat_map(|i| (0..34).map(move |j| (i, j))) {
        let (x, z) = (i as f32 * 0.03 - 0.5, j as f32 * 0.03 - 0.8);
        objects.push(at(Vec3::new(x, 1.2 + (i + j) as f32 % 5.0 * 0.1, z), 0.01));
    }
    let scene = Scene {
        objects,
        lights: vec![Light::Point {
            position: Vec3::new(-0.5, 1.0, 0.8),
            color: Vec3::ONE,
        }],
        camera: Camera {
            position: Vec3::new(0.0, 0.5, 1.0),
            look_at: Vec3::ZERO,
            fov_deg: 40.0,
        },
        size: (72, 40),
        max_depth: 3,
        samples: 1,
        ..Scene::default()
    };
    assert_fast_is_full(&scene, "packets past the scan limit");
}
