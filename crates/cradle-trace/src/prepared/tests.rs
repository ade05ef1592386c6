//! A plane's own rays do not test it, in every renderer: the nearest-hit and
//! any-hit queries with and without shadow culling and the hierarchy.

use crate::geometry::Ray;
use crate::prepared::Prepared;
use crate::scene::{Light, Material, Object, Scene, Shape};
use glam::Vec3;

/// A floor (object 0, y = 0) and a ball above it (object 1), one point light.
fn floor_and_ball() -> Scene {
    let object = |shape| Object {
        shape,
        material: Material {
            color: Vec3::splat(0.5),
            specular: None,
            reflective: 0.5,
            checker: None,
        },
        moving: false,
    };
    Scene {
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
            position: Vec3::new(0.3, 1.0, 0.0),
            color: Vec3::ONE,
        }],
        ..Scene::default()
    }
}

#[test]
fn a_planes_own_rays_do_not_test_it() {
    let scene = floor_and_ball();
    // From 1 mm below the floor straight up, clear of the ball: it crosses the
    // floor at t = 1e-3, as a far point's rounding could start one.
    let ray = Ray {
        origin: Vec3::new(0.3, -1e-3, 0.0),
        dir: Vec3::Y,
    };
    let inf = f32::INFINITY;
    for (culling, bvh) in [(false, false), (true, false), (false, true), (true, true)] {
        let p = Prepared::new(&scene)
            .with_shadow_culling(culling)
            .with_bvh(bvh);
        let setup = format!("culling {culling}, hierarchy {bvh}");
        // Any other ray meets the floor there (1e-3 to within f32 rounding).
        let hit = p.closest(&ray, inf).expect("the floor");
        assert_eq!(hit.object, 0, "{setup}");
        assert!((hit.t - 1e-3).abs() < 1e-7, "{setup}: t = {}", hit.t);
        assert!(p.occluded_by_planes(usize::MAX, &ray, 1.0), "{setup}");
        assert!(p.occluded(&ray, 1.0), "{setup}");
        // The ball's own rays too: the rule is a plane's only.
        assert!(p.occluded_towards((1, true), 0, &ray, 1.0), "{setup}");
        assert_eq!(
            p.closest_from(Some((1, false)), &ray, inf)
                .map(|h| h.object),
            Some(0)
        );
        // The floor's own rays do not.
        for outside in [true, false] {
            assert!(
                p.closest_from(Some((0, outside)), &ray, inf).is_none(),
                "{setup}"
            );
            assert!(!p.occluded_towards((0, outside), 0, &ray, 1.0), "{setup}");
        }
        assert!(!p.occluded_by_planes(0, &ray, 1.0), "{setup}");
        // Nor do the floor's mirror rays through a tile's list.
        assert!(
            p.closest_among(&ray, inf, (&[0, 1], 0)).is_none(),
            "{setup}"
        );
        let primary = p.closest_among(&ray, inf, (&[0, 1], usize::MAX));
        assert_eq!(primary.map(|h| h.object), Some(0), "{setup}");
    }
}

#[test]
fn a_balls_own_mirror_ray_rounds_the_same_way_in_every_renderer() {
    // A second bounce off a ball (centre (0.04, 0.09, 0), r = 0.02), seen in
    // a swinging cradle: the ray starts 1.02e-5 m outside the ball and runs
    // away from it, but its direction is 0.14% short of unit length, and the
    // sphere test rounds to a hit at t = 1.23e-5, just past T_MIN (numpy's f32
    // gives the same). The hierarchy once skipped the ball as "clearly
    // outside" while the reference found it: one pixel off by one.
    let mut scene = floor_and_ball();
    scene.objects[1].shape = Shape::Sphere {
        centre: Vec3::new(0.04, 0.09, 0.0),
        radius: 0.02,
    };
    let ray = Ray {
        origin: Vec3::new(0.056_528_3, 0.101_239_79, -0.000_943_438_4),
        dir: Vec3::new(0.429_356_87, 0.895_255_6, -0.106_650_91),
    };
    let key = |bvh: bool| {
        Prepared::new(&scene)
            .with_bvh(bvh)
            .closest_from(Some((1, true)), &ray, f32::INFINITY)
            .map(|h| (h.object, h.t.to_bits()))
    };
    let reference = key(false);
    assert_eq!(reference.map(|(o, _)| o), Some(1), "the rounding hit");
    assert_eq!(key(true), reference, "the hierarchy finds the same");
}
