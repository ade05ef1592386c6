//! The lanes' box, sphere and cylinder tests (portable and AVX2 builds) against
//! the scalar ones, lane by lane, on rays of every kind: random, along the axes
//! (zero direction components, infinite inverses), from inside, grazing, along
//! a cylinder's axis (caps only) and across it.

use super::LANES;
use super::hits::{blocks8, box8};
use super::lights::base_lanes;
use super::lookup::lookup;
use super::vec::{F8, L3, V8, load3, store3};
use crate::geometry::Geom;
use crate::geometry::{Aabb, Cylinder, Ray, hit_sphere};
use crate::scene::Material;
use crate::simd::{Portable, Simd};
use glam::Vec3;

struct Lcg(u32);
impl Lcg {
    fn f(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (self.0 >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
    }
    fn v(&mut self) -> Vec3 {
        Vec3::new(self.f(), self.f(), self.f())
    }
}

/// Eight rays: random ones, axis-aligned ones and ones aimed at `target`.
fn rays(rng: &mut Lcg, target: Vec3, round: usize) -> [Ray; LANES] {
    std::array::from_fn(|i| {
        let origin = match round % 3 {
            0 => target + rng.v() * 0.5,
            1 => target + rng.v() * 0.01,
            _ => Vec3::new(target.x, target.y + 0.3, target.z),
        };
        let dir = match (round + i) % 4 {
            0 => (target + rng.v() * 0.03 - origin).normalize(),
            1 => [Vec3::X, -Vec3::Y, Vec3::Z, -Vec3::X][i % 4],
            2 => rng.v().normalize(),
            _ => (target - origin).normalize(),
        };
        Ray { origin, dir }
    })
}

fn lanes_of(rays: &[Ray; LANES]) -> (V8, V8, V8) {
    let v = |f: &dyn Fn(&Ray) -> Vec3| V8 {
        x: std::array::from_fn(|i| f(&rays[i]).x),
        y: std::array::from_fn(|i| f(&rays[i]).y),
        z: std::array::from_fn(|i| f(&rays[i]).z),
    };
    (v(&|r| r.origin), v(&|r| r.dir), v(&|r| r.dir.recip()))
}

/// The box, sphere, string and rod tests of the lanes `(o, d, inv)` in build
/// `s`, as bits.
fn four<S: Simd>(
    s: S,
    (boxed, shapes): (&Aabb, &[Geom; 3]),
    (o, d, inv): &(V8, V8, V8),
    t_max: f32,
) -> [u8; 4] {
    let (o, d, inv) = (load3(s, o), load3(s, d), load3(s, inv));
    let t = s.splat(t_max);
    let hit = |g: &Geom| S::bits(blocks8(s, g, (&o, &d), t, 0xFF));
    [
        S::bits(box8(s, boxed, &o, &inv, t)),
        hit(&shapes[0]),
        hit(&shapes[1]),
        hit(&shapes[2]),
    ]
}

/// `f(build)` for the portable build and, where the CPU has it, the AVX2 one.
macro_rules! each_build {
    ($f:expr) => {{
        #[cfg(target_arch = "x86_64")]
        let avx = crate::simd::Avx2::detect().map(|s| $f(s));
        #[cfg(not(target_arch = "x86_64"))]
        let avx = None;
        std::iter::once($f(Portable)).chain(avx).collect::<Vec<_>>()
    }};
}

const NAMES: [&str; 4] = ["box", "sphere", "string", "rod"];

#[test]
fn lane_tests_answer_as_the_scalar_tests() {
    let mut rng = Lcg(3);
    let centre = Vec3::new(0.02, 0.09, -0.01);
    let sphere = Geom::Sphere {
        centre,
        radius: 0.02,
    };
    let (a, b) = (Vec3::new(0.0, 0.25, -0.05), Vec3::new(0.01, 0.11, 0.0));
    let cyl = Cylinder::new(a, b, 0.0006);
    let rod = Cylinder::new(
        Vec3::new(-0.2, 0.25, 0.05),
        Vec3::new(0.2, 0.25, 0.05),
        0.005,
    );
    let boxed = Aabb {
        min: centre - 0.02,
        max: centre + 0.02,
    };
    let mut seen = [0u32; 4];
    for round in 0..600 {
        let target = match round % 3 {
            0 => centre,
            1 => (a + b) * 0.5,
            _ => Vec3::new(0.1, 0.25, 0.05),
        };
        let r = rays(&mut rng, target, round);
        let lanes = lanes_of(&r);
        let shapes = [sphere, Geom::Cylinder(cyl), Geom::Cylinder(rod)];
        for t_max in [f32::INFINITY, 0.3, 0.01] {
            let builds = each_build!(|s| four(s, (&boxed, &shapes), &lanes, t_max));
            for got in builds {
                for (i, ray) in r.iter().enumerate() {
                    let want = [
                        boxed.hit(ray, ray.dir.recip(), t_max),
                        hit_sphere(ray, centre, 0.02).is_some_and(|t| t < t_max),
                        cyl.hit(ray).is_some_and(|(t, _)| t < t_max),
                        rod.hit(ray).is_some_and(|(t, _)| t < t_max),
                    ];
                    for (k, (&bits, want)) in got.iter().zip(want).enumerate() {
                        let on = bits >> i & 1 != 0;
                        assert_eq!(on, want, "{} {ray:?} {t_max}", NAMES[k]);
                        seen[k] += u32::from(on);
                    }
                }
            }
        }
    }
    // Each test both hit and missed many times (14,400 lane tests per build).
    for (what, n) in NAMES.iter().zip(seen) {
        assert!(n > 300 && n < 14_000, "{what}: {n} hits");
    }
}

#[test]
fn lane_lookups_find_the_scalar_cells() {
    use crate::scene::Light;
    use crate::shadow::{Footprints, Lookup};
    let bounded: Vec<(usize, Aabb)> = (0..7)
        .map(|i| {
            let c = Vec3::new(i as f32 * 0.04 - 0.12, 0.09, 0.0);
            (
                i + 1,
                Aabb {
                    min: c - 0.02,
                    max: c + 0.02,
                },
            )
        })
        .collect();
    let lights = [
        Light::Point {
            position: Vec3::new(-0.6, 0.9, 0.8),
            color: Vec3::ONE,
        },
        Light::Point {
            position: Vec3::new(0.05, 0.12, 0.0),
            color: Vec3::ONE,
        },
        Light::Directional {
            direction: Vec3::new(0.3, -1.0, -0.2).normalize(),
            color: Vec3::ONE,
        },
    ];
    let mut rng = Lcg(5);
    let mut kinds = [0u32; 3];
    for light in &lights {
        let fp =
            Footprints::new(Vec3::ZERO, Vec3::Y, light, &bounded, |_| Vec::new()).expect("lit");
        for round in 0..500 {
            // Starts just off the floor near the cradle and far out, some below
            // it, some as high as the low light.
            let start = V8 {
                x: std::array::from_fn(|_| rng.f() * if round % 2 == 0 { 0.3 } else { 3.0 }),
                y: std::array::from_fn(|i| match (round + i) % 5 {
                    0 => -1e-5,
                    1 => 0.12 + rng.f() * 1e-3,
                    _ => 2e-5,
                }),
                z: std::array::from_fn(|_| rng.f() * 0.3),
            };
            let builds = each_build!(|s| lookup(s, &fp.view(), &load3(s, &start)));
            for (i, want) in (0..LANES).map(|i| (i, fp.lookup(start.lane(i)))) {
                for got in &builds {
                    assert_eq!(Lookup::of(got[i]), want, "{light:?} at {:?}", start.lane(i));
                }
                kinds[match want {
                    Lookup::Unlit => 0,
                    Lookup::Always => 1,
                    Lookup::Cell(_) => 2,
                }] += 1;
            }
        }
    }
    assert!(
        kinds.iter().all(|&k| k > 100),
        "every kind of answer: {kinds:?}"
    );
}

/// The checker colours of eight floor points by `base_lanes` in `s`.
fn checker_lanes<S: Simd>(s: S, material: &Material, x: &F8, z: &F8) -> V8 {
    let point = L3 {
        x: s.load(x),
        y: s.splat(0.0),
        z: s.load(z),
    };
    store3::<S>(&base_lanes(s, material, &point))
}

#[test]
fn checker_lanes_pick_the_scalar_colours() {
    use crate::material::base_color;
    let material = Material {
        color: Vec3::new(0.32, 0.22, 0.14),
        specular: None,
        reflective: 0.0,
        checker: Some((Vec3::new(0.26, 0.17, 0.1), 0.05)),
    };
    // Cell borders (exact multiples of the size and their neighbours), signed
    // zeros, the edge of the exact range (2^22 cells) and beyond it, huge
    // values, infinities and NaN: the far ones take the scalar path per lane.
    let mut special = vec![0.0, -0.0, 0.05, -0.05, 0.1, -0.1, 1e-9, -1e-9];
    for c in [1.0f32, 3.0, 2_097_151.0, 4_194_303.0, 4_194_304.0, 9e6] {
        let v = c * 0.05;
        special.extend([v, -v, v.next_up(), (-v).next_down(), v.next_down()]);
    }
    special.extend([
        1e20,
        -1e20,
        3e38,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ]);
    // The near values first: packets of them take the lanes' own parity.
    let near = special.iter().filter(|v| v.abs() < 200_000.0).count();
    special.sort_by_key(|v| v.abs() >= 200_000.0 || v.is_nan());
    let mut rng = Lcg(11);
    let mut pick = |round: usize, i: usize| -> f32 {
        match round % 4 {
            1 => special[(round * 7 + i * 13) % near],
            2 if i == round % LANES => special[near + round % (special.len() - near)],
            0 | 2 => rng.f() * 2.0,
            _ => special[(round * 7 + i * 13) % special.len()],
        }
    };
    for round in 0..2000 {
        let x: F8 = std::array::from_fn(|i| pick(round, i));
        let z: F8 = std::array::from_fn(|i| pick(round + 1, i + 3));
        for got in each_build!(|s| checker_lanes(s, &material, &x, &z)) {
            for i in 0..LANES {
                let want = base_color(&material, Vec3::new(x[i], 0.0, z[i]));
                assert_eq!(got.lane(i), want, "at x {} z {}", x[i], z[i]);
            }
        }
    }
}

/// The lanes' nearest hit on a shape and the normal there (`hit_part`, then
/// `normal_at`, as a bounce takes them from its nearest-hit scan), and
/// `hit_normal` (without the scan), are the scalar `Prepared::hit_object`'s
/// bit for bit, where it meets the shape; +inf where it does not.
#[test]
fn lane_hits_and_normals_are_the_scalar_ones() {
    let mut rng = Lcg(11);
    let centre = Vec3::new(0.02, 0.09, -0.01);
    let (a, b) = (Vec3::new(0.0, 0.25, -0.05), Vec3::new(0.01, 0.11, 0.0));
    let shapes = [
        Geom::Sphere {
            centre,
            radius: 0.02,
        },
        Geom::Cylinder(Cylinder::new(a, b, 0.0006)),
        Geom::Cylinder(Cylinder::new(b, b + Vec3::X * 0.1, 0.02)),
    ];
    let (mut hits, mut caps) = (0, 0);
    for round in 0..600 {
        let target = [centre, (a + b) * 0.5, b + Vec3::X * 0.05][round % 3];
        let r = rays(&mut rng, target, round);
        let (o, d, _) = lanes_of(&r);
        for g in &shapes {
            let want: [_; LANES] = std::array::from_fn(|i| match *g {
                Geom::Sphere { centre, radius } => {
                    hit_sphere(&r[i], centre, radius).map(|t| (t, (r[i].at(t) - centre) / radius))
                }
                Geom::Cylinder(c) => c.hit(&r[i]),
                Geom::Plane { .. } => unreachable!(),
            });
            for (t, part, n, t2, n2) in each_build!(|s| hit_lanes(s, g, &o, &d)) {
                for (i, w) in want.iter().enumerate() {
                    assert_eq!(t[i].to_bits(), t2[i].to_bits());
                    let Some((wt, wn)) = *w else {
                        assert_eq!(t[i], f32::INFINITY, "{:?}", r[i]);
                        continue;
                    };
                    assert_eq!(t[i].to_bits(), wt.to_bits(), "{:?}", r[i]);
                    for got in [n.lane(i), n2.lane(i)] {
                        assert_eq!(
                            got.to_array().map(f32::to_bits),
                            wn.to_array().map(f32::to_bits)
                        );
                    }
                    hits += 1;
                    caps += u32::from(part[i] > 0.0);
                }
            }
        }
    }
    // Many hits, and among them the caps of the wide cylinder.
    assert!(hits > 2000 && caps > 50, "{hits} hits, {caps} on caps");
}

/// Per lane of build `s`: `hit_part`'s `t` and part, `normal_at` there, and
/// `hit_normal`'s `t` and normal.
fn hit_lanes<S: Simd>(s: S, g: &Geom, o: &V8, d: &V8) -> (F8, F8, V8, F8, V8) {
    use super::hits::{hit_normal, hit_part, normal_at};
    let (o, d) = (load3(s, o), load3(s, d));
    let (t, part) = hit_part(s, g, (&o, &d), 0xFF);
    let n = normal_at(s, g, (&o, &d), (t, part));
    let (t2, n2) = hit_normal(s, g, &o, &d);
    (
        S::store(t),
        S::store(part),
        store3::<S>(&n),
        S::store(t2),
        store3::<S>(&n2),
    )
}

mod highlights;
mod wanted;
