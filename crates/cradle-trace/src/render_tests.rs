//! Packets in tracked frames note the motion cells and segments the scalar path
//! notes.

use super::{Frame, RenderOptions};
use crate::motion::Seg;
use crate::retrace::RowMotion;
use crate::scene::{Camera, Light, Material, Object, Scene, Shape};
use glam::Vec3;

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
    };
    let (fast_img, fast_rows) = Frame::new(&scene, RenderOptions::FAST, true).image(false);
    let (full_img, full_rows) = Frame::new(&scene, RenderOptions::FULL, true).image(false);
    assert!(fast_img == full_img, "the same picture");
    let cells = |rows: &[RowMotion]| {
        rows.iter()
            .flat_map(|r| r.cells.clone())
            .collect::<Vec<_>>()
    };
    let (fast, full) = (cells(&fast_rows), cells(&full_rows));
    let differing = fast.iter().zip(&full).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "pixels whose motion cells differ");
    assert!(
        full.iter().filter(|&&m| m != 0).count() > 1000,
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
