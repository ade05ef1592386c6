//! A plane's own rays do not test it, in every renderer: the nearest-hit and
//! any-hit queries with and without shadow culling and the hierarchy.

use crate::geometry::Ray;
use crate::prepared::Prepared;
use crate::scene::{Light, Material, Object, Scene, Shape};
use glam::Vec3;

/// A static grey object of `shape`, half a mirror.
fn object(shape: Shape) -> Object {
    Object {
        shape,
        material: Material {
            color: Vec3::splat(0.5),
            specular: None,
            reflective: 0.5,
            checker: None,
        },
        moving: false,
    }
}

/// A floor (object 0, y = 0) and a ball above it (object 1), one point light.
fn floor_and_ball() -> Scene {
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

/// Casters kept from the frame before, where no moved object can enter their
/// lists, hold the objects that casters found afresh hold: a row of balls
/// under a rod, two point lights, the first ball swung out to the side.
#[test]
fn kept_casters_hold_what_fresh_ones_hold() {
    use crate::casters::Casters;
    use crate::geometry::bounds;
    use crate::prepared::Kept;
    let ball = |x: f32, y: f32| {
        object(Shape::Sphere {
            centre: Vec3::new(x, y, 0.0),
            radius: 0.02,
        })
    };
    let mut objects = vec![object(Shape::Plane {
        point: Vec3::ZERO,
        normal: Vec3::Y,
    })];
    objects.extend((0..5).map(|k| ball(-0.08 + 0.04 * k as f32, 0.1)));
    objects.push(object(Shape::Cylinder {
        a: Vec3::new(-0.2, 0.3, 0.0),
        b: Vec3::new(0.2, 0.3, 0.0),
        radius: 0.005,
    }));
    let point = |position| Light::Point {
        position,
        color: Vec3::ONE,
    };
    let before = Scene {
        objects,
        lights: vec![
            point(Vec3::new(0.3, 1.0, 0.5)),
            point(Vec3::new(-0.6, 0.8, 0.2)),
        ],
        ..Scene::default()
    };
    let mut after = before.clone();
    after.objects[1] = ball(-0.2, 0.16);
    let moved = [
        bounds(&before.objects[1].shape),
        bounds(&after.objects[1].shape),
    ]
    .map(|b| b.expect("a ball has a box"));
    let kept = Kept {
        casters: Prepared::new(&before)
            .with_shadow_culling(true)
            .take_casters()
            .expect("shadow culling is on"),
        footprints: None,
        moved: vec![1],
        boxes: moved.to_vec(),
    };
    let fresh = Prepared::new(&after).with_shadow_culling(true);
    let reused = Prepared::new(&after).with_shadow_culling_kept(true, Some(kept));
    let keeps: Vec<bool> = after
        .objects
        .iter()
        .map(|o| Casters::keep_for(&o.shape, &after.lights, &moved))
        .collect();
    assert!(keeps[2..].iter().any(|&k| k), "no object keeps its casters");
    assert!(
        keeps[2..].iter().any(|&k| !k),
        "every object keeps its casters"
    );
    let mut lists = 0;
    for i in 1..after.objects.len() {
        let (f, r) = (
            fresh.casters(i).expect("bounded"),
            reused.casters(i).expect("bounded"),
        );
        for light in 0..after.lights.len() {
            for piece in 0..16 {
                for outside in [false, true] {
                    let items = |c: &Casters| {
                        let mut v: Vec<usize> = c
                            .list(light, piece.min(c.axis().3 - 1), outside)
                            .expect("a point light's list")
                            .items()
                            .collect();
                        v.sort_unstable();
                        v
                    };
                    assert_eq!(items(f), items(r), "object {i} light {light} piece {piece}");
                    lists += 1;
                }
            }
        }
    }
    assert!(lists > 0);
}
