//! Hit points stay on the surface when the eye is far: from up to 10 m (the
//! config's camera limit), a ray's hit on a 2 cm ball or a 0.6 mm string must
//! lie on the surface to far better than the offset secondary rays start at
//! (2e-5 m), or the surface shadows itself in speckles and rings. And that
//! offset keeps a mirror ray off the convex object it leaves, which the fast
//! path relies on to skip that object.

use cradle_trace::geometry::{Cylinder, Ray, hit_sphere};
use cradle_trace::{Camera, Material, Object, Prepared, Scene, Shape};
use glam::{DVec3, Vec3};

/// f32 coordinates near 10 m are spaced 1e-6 m apart, and the hit point is
/// `origin + dir * t` rounded at that scale: a few of those spacings is the best
/// f32 can promise, and ten times below the 2e-5 m surface offset.
const ON_SURFACE: f64 = 3e-6;

/// A small deterministic generator (no dependency): uniform in 0..1.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(self.next(), self.next(), self.next()) * 2.0 - 1.0;
            if v.length_squared() > 1e-3 && v.length_squared() <= 1.0 {
                return v.normalize();
            }
        }
    }
}

/// An eye 5 to 10 m from `target` (within +-10 m of the origin), and the f32
/// ray from it towards `target`.
fn far_ray(rng: &mut Lcg, target: DVec3) -> Ray {
    let mut eye = target + rng.unit() * (5.0 + 5.0 * rng.next());
    eye = eye.clamp(DVec3::splat(-9.9), DVec3::splat(9.9));
    let origin = eye.as_vec3();
    Ray {
        origin,
        dir: (target - origin.as_dvec3()).normalize().as_vec3(),
    }
}

#[test]
fn a_far_eye_hits_a_ball_on_its_surface() {
    let mut rng = Lcg(7);
    let (centre, radius) = (Vec3::new(0.3, 0.09, 0.1), 0.02_f32);
    let mut worst = 0.0_f64;
    for _ in 0..20_000 {
        // Aim within 0.95 of the radius, so every ray hits.
        let target = centre.as_dvec3() + rng.unit() * 0.95 * f64::from(radius);
        let ray = far_ray(&mut rng, target);
        let t = hit_sphere(&ray, centre, radius).expect("aimed at the ball");
        let p = ray.at(t).as_dvec3();
        let off = ((p - centre.as_dvec3()).length() - f64::from(radius)).abs();
        worst = worst.max(off);
    }
    assert!(
        worst <= ON_SURFACE,
        "a hit point is {worst:.2e} m off the ball"
    );
}

#[test]
fn a_far_eye_hits_a_string_on_its_surface() {
    let mut rng = Lcg(11);
    let (a, b, radius) = (
        Vec3::new(-0.1, 0.25, -0.05),
        Vec3::new(-0.1, 0.11, 0.0),
        0.0006_f32,
    );
    let cyl = Cylinder::new(a, b, radius);
    let (ad, bd) = (a.as_dvec3(), b.as_dvec3());
    let u = (bd - ad).normalize();
    let mut worst = 0.0_f64;
    let mut hits = 0;
    for _ in 0..20_000 {
        // Aim at a point within 0.9 of the radius of the axis, mid-length.
        let along = 0.1 + 0.8 * rng.next();
        let side = rng.unit().reject_from(u) * 0.9 * f64::from(radius) * rng.next();
        let target = ad + (bd - ad) * along + side;
        let ray = far_ray(&mut rng, target);
        let Some((t, _)) = cyl.hit(&ray) else {
            continue;
        };
        hits += 1;
        let p = ray.at(t).as_dvec3() - ad;
        let axial = p.dot(u);
        let radial = (p - u * axial).length();
        // A body hit is at the radius; a cap hit (a ray nearly along the axis)
        // lies in an end plane.
        let off = (radial - f64::from(radius))
            .abs()
            .min(axial.abs())
            .min((axial - (bd - ad).length()).abs());
        worst = worst.max(off);
    }
    assert!(hits > 19_000, "only {hits} of 20000 aimed rays hit");
    assert!(
        worst <= ON_SURFACE,
        "a hit point is {worst:.2e} m off the string"
    );
}

#[test]
fn a_mirror_ray_never_meets_the_convex_object_it_leaves() {
    // A ball, a tilted rod and a floor, hit from all around (many grazing):
    // the mirror ray, made as `shade` makes it, is never stopped by the object
    // it leaves when met from outside, so skipping that object (the fast
    // path) finds exactly the reference's hit.
    let steel = Material {
        color: Vec3::splat(0.5),
        specular: None,
        reflective: 0.5,
        checker: None,
    };
    let sphere = |centre: Vec3, radius: f32, material: Material| Object {
        shape: Shape::Sphere { centre, radius },
        material,
        moving: false,
    };
    let objects = vec![
        Object {
            shape: Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            material: steel,
            moving: false,
        },
        sphere(Vec3::new(0.0, 0.05, 0.0), 0.02, steel),
        sphere(Vec3::new(0.04, 0.05, 0.0), 0.02, steel),
        Object {
            shape: Shape::Cylinder {
                a: Vec3::new(-0.1, 0.2, 0.05),
                b: Vec3::new(0.1, 0.23, -0.02),
                radius: 0.005,
            },
            material: steel,
            moving: false,
        },
    ];
    let s = Scene {
        objects,
        lights: vec![],
        camera: Camera {
            position: Vec3::new(0., 0., 5.),
            look_at: Vec3::ZERO,
            fov_deg: 30.0,
        },
        background: Vec3::ZERO,
        size: (8, 8),
        max_depth: 3,
        samples: 1,
        adaptive: None,
        motion_bounds: None,
        coarse: 1,
    };
    let full = Prepared::new(&s);
    let fast = Prepared::new(&s).with_bvh(true);
    let mut seed = 7u32;
    let mut rnd = || {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (seed >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
    };
    let (mut skipped, mut grazing) = (0, 0);
    for k in 0..20_000 {
        let mut target = Vec3::new(rnd() * 0.12, 0.05 + rnd() * 0.18, rnd() * 0.06);
        let origin = target + Vec3::new(rnd(), rnd().abs() + 0.05, rnd()).normalize() * 0.5;
        if k % 4 == 0 {
            // Just inside the first ball's rim as seen from `origin`: grazing.
            let centre = Vec3::new(0.0, 0.05, 0.0);
            let side = (centre - origin).any_orthonormal_vector();
            target = centre + side * 0.02 * 0.9999;
        }
        let r = Ray {
            origin,
            dir: (target - origin).normalize(),
        };
        let Some(hit) = full.closest(&r, f32::INFINITY) else {
            continue;
        };
        // As `shade` does: 2e-5 m off the surface, the mirrored direction.
        let n = hit.normal;
        let dir = r.dir - 2.0 * r.dir.dot(n) * n;
        let mirror = Ray {
            origin: r.at(hit.t) + n * 2e-5,
            dir,
        };
        grazing += usize::from(r.dir.dot(n).abs() < 0.05);
        let want = full.closest(&mirror, f32::INFINITY);
        let from = Some((hit.object, hit.outside));
        let got = fast.closest_from(from, &mirror, f32::INFINITY);
        assert_eq!(
            want.map(|h| (h.t.to_bits(), h.object)),
            got.map(|h| (h.t.to_bits(), h.object)),
            "{r:?}"
        );
        if hit.outside {
            skipped += 1;
            assert_ne!(want.map(|h| h.object), Some(hit.object), "{r:?}");
        }
    }
    assert!(skipped > 5_000 && grazing > 100, "{skipped} {grazing}");
    // From inside a ball (as a reflection starting within a touching
    // neighbour is), the ball itself is still met.
    let inside = Ray {
        origin: Vec3::new(0.0, 0.05, 0.0),
        dir: Vec3::X,
    };
    let got = fast.closest_from(Some((1, false)), &inside, f32::INFINITY);
    assert_eq!(got.map(|h| h.object), Some(1));
}
