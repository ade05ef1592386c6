//! The cylinder test's short cuts: only the lanes a caller wants need be
//! right, so the test stops early where every wanted lane misses the infinite
//! cylinder (`hit_part`), or where every wanted lane is already blocked
//! before the caps (`blocks8`). Wanted lanes must still answer as the scalar
//! `Cylinder::hit` does, whatever the other lanes hold.

use super::super::LANES;
use super::super::hits::{blocks8, hit_part};
use super::super::vec::{V8, load3};
use super::{Lcg, lanes_of, rays};
use crate::geometry::Cylinder;
use crate::geometry::Geom;
use crate::simd::{Portable, Simd};
use glam::Vec3;

/// Per lane of `want`, in build `s`: `hit_part`'s `t` (as bits) and
/// `blocks8`'s answer before `t_max`.
fn wanted<S: Simd>(
    s: S,
    g: &Geom,
    (o, d): (&V8, &V8),
    (want, t_max): (u8, f32),
) -> ([u32; LANES], u8) {
    let (o, d) = (load3(s, o), load3(s, d));
    let t = S::store(hit_part(s, g, (&o, &d), want).0).map(f32::to_bits);
    let blocked = S::bits(blocks8(s, g, (&o, &d), s.splat(t_max), want));
    (t, blocked & want)
}

#[test]
fn wanted_lanes_answer_as_the_scalar_test_whatever_the_others_hold() {
    let mut rng = Lcg(5);
    let string = Cylinder::new(
        Vec3::new(0.0, 0.25, -0.05),
        Vec3::new(0.01, 0.11, 0.0),
        0.0006,
    );
    let rod = Cylinder::new(
        Vec3::new(-0.2, 0.25, 0.05),
        Vec3::new(0.2, 0.25, 0.05),
        0.005,
    );
    // (all wanted lanes missed, some wanted lane hit)
    let mut seen = (0u32, 0u32);
    for round in 0..400 {
        for c in [string, rod] {
            let target = (c.parts().0 + c.parts().1) * 0.5;
            let r = rays(&mut rng, target, round);
            let (o, d, _) = lanes_of(&r);
            let scalar: [Option<f32>; LANES] =
                std::array::from_fn(|i| c.hit(&r[i]).map(|(t, _)| t));
            let g = Geom::Cylinder(c);
            for want in (0..LANES)
                .map(|i| 1u8 << i)
                .chain([0x0F, 0xA5, 0xFF, rng.0 as u8])
            {
                for t_max in [f32::INFINITY, 0.05] {
                    let mut builds = vec![wanted(Portable, &g, (&o, &d), (want, t_max))];
                    #[cfg(target_arch = "x86_64")]
                    if let Some(a) = crate::simd::Avx2::detect() {
                        builds.push(wanted(a, &g, (&o, &d), (want, t_max)));
                    }
                    for (t, blocked) in builds {
                        for i in (0..LANES).filter(|i| want >> i & 1 != 0) {
                            let hit = scalar[i].unwrap_or(f32::INFINITY);
                            assert_eq!(t[i], hit.to_bits(), "{:?} lane {i} of {want:08b}", r[i]);
                            let on = blocked >> i & 1 != 0;
                            assert_eq!(on, hit < t_max, "{:?} lane {i} of {want:08b}", r[i]);
                        }
                    }
                    let any = (0..LANES).any(|i| want >> i & 1 != 0 && scalar[i].is_some());
                    if any {
                        seen.1 += 1;
                    } else {
                        seen.0 += 1;
                    }
                }
            }
        }
    }
    // Both the early ends and the full tests ran many times.
    assert!(seen.0 > 1000 && seen.1 > 1000, "{seen:?}");
}
