//! The shadow rays of lanes on a bounded object (the cradle), over the lanes:
//! each tested against the object's casters (`Prepared::occluded_towards`'
//! list, per piece of the object and per side).

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::hits::recip;
use super::occlusion::Rays;
use super::{L3, LANES, Packet, lanes_with, splat3};
use crate::casters::MARGIN;
use crate::geometry::Geom;
use crate::simd::Simd;
use glam::Vec3;

impl Packet<'_, '_> {
    /// Per lane (bits), `Prepared::occluded_towards` for the shadow rays of
    /// the lanes in `want` from `start` along `dir` to `dist`, towards light `li`
    /// from points of `object` met from outside in the lanes of `outside`: the
    /// planes, then the casters of the piece each lane starts from (lanes with
    /// the same list tested together), or every bounded object where there are
    /// no lists. An "any hit" answer, so the order of the tests does not matter.
    /// `key`: each lane's piece and side ([`Self::caster_keys`]).
    #[inline(always)]
    pub(super) fn object_shadows<S: Simd>(
        &self,
        s: S,
        (object, li, key): (usize, usize, &[(usize, bool); LANES]),
        (start, dir, dist): (&L3<S::F>, &L3<S::F>, S::F),
        want: u8,
    ) -> u8 {
        let p = self.p;
        let mut out = self.planes_before(s, (object, start, dir), dist, want);
        let mut todo = want & !out;
        if todo == 0 {
            return out;
        }
        let rays = Rays {
            start,
            dir,
            inv: recip(s, dir),
            dist,
        };
        let casters = p.casters(object);
        while todo != 0 {
            let first = key[todo.trailing_zeros() as usize];
            let group = lanes_with(key, &first, todo);
            out |= match casters.and_then(|c| c.list(li, first.0, first.1)) {
                Some(list) => self.blocked_by(s, list.items(), &rays, group & !out),
                None => self.blocked_by(s, p.bounded.iter().map(|b| b.0), &rays, group & !out),
            };
            todo &= !group;
        }
        out
    }

    /// Per lane of `on`, the piece of `object` its shadow rays start from (at
    /// `start`) and whether they start clearly outside it, having met it from
    /// outside (`outside`): which of the object's caster lists it takes, for
    /// every light.
    #[inline(always)]
    pub(super) fn caster_keys<S: Simd>(
        &self,
        s: S,
        object: usize,
        (outside, on): (u8, u8),
        start: &L3<S::F>,
    ) -> [(usize, bool); LANES] {
        let p = self.p;
        let Some(c) = p.casters(object) else {
            return [(0, false); LANES];
        };
        let pieces = piece_lanes(s, c.axis(), start);
        let clear = outside & S::bits(clear_lanes(s, p.geom(object), start));
        let mut key = [(0, false); LANES];
        for (i, k) in key.iter_mut().enumerate() {
            if on >> i & 1 != 0 {
                *k = (pieces[i] as usize, clear >> i & 1 != 0);
            }
        }
        key
    }
}

/// `Casters::piece` per lane, with the same operations: `s = (at - a).dot(u)
/// / len * pieces`, then `(s.max(0.0) as usize).min(pieces - 1)`, here as
/// `max(s, 0)` (0 for NaN, as `f32::max`), `min` with `pieces - 1` (exact in
/// `f32`) and a truncation of a value in `0..=pieces - 1`.
#[inline(always)]
fn piece_lanes<S: Simd>(
    s: S,
    (a, u, len, pieces): (Vec3, Vec3, f32, usize),
    at: &L3<S::F>,
) -> [i32; LANES] {
    if pieces == 1 {
        return [0; LANES];
    }
    let k = |v: f32| s.splat(v);
    let along = at.sub(&splat3(s, a)).dot(&splat3(s, u)) / k(len) * k(pieces as f32);
    S::trunc(S::min(S::max(along, k(0.0)), k((pieces - 1) as f32)))
}

/// `casters::clear_of` per lane, with the same operations: a sphere's
/// `(p - centre).length_squared() > (radius + MARGIN)^2`; a cylinder's axial
/// position beyond either cap by more than `MARGIN`, or the offset from the
/// axis, `p - a - u * s`, longer than `radius + MARGIN`; planes: always.
#[inline(always)]
fn clear_lanes<S: Simd>(s: S, g: &Geom, p: &L3<S::F>) -> S::M {
    let k = |v: f32| s.splat(v);
    match *g {
        Geom::Sphere { centre, radius } => {
            let d = p.sub(&splat3(s, centre));
            S::lt(k((radius + MARGIN) * (radius + MARGIN)), d.dot(&d))
        }
        Geom::Cylinder(ref c) => {
            let (a, _, u, len, radius) = c.parts();
            let pa = p.sub(&splat3(s, a));
            let along = pa.dot(&splat3(s, u));
            let beyond = S::lt(along, k(-MARGIN)) | S::lt(k(len + MARGIN), along);
            let off = pa.sub(&splat3(s, u).scale(along));
            beyond | S::lt(k((radius + MARGIN) * (radius + MARGIN)), off.dot(&off))
        }
        Geom::Plane { .. } => s.mask(0xFF),
    }
}

#[cfg(test)]
mod tests {
    use super::{clear_lanes, piece_lanes};
    use crate::casters::{Casters, clear_of};
    use crate::geometry::Geom;
    use crate::packet::vec::L3;
    use crate::scene::{Light, Shape};
    use crate::simd::{Portable, Simd};
    use glam::Vec3;

    /// Both lane builds' pieces and sides equal `Casters::piece` and
    /// `clear_of` point by point, around a sphere and a tilted rod: points
    /// just inside and outside the 1e-5 m margin, beyond the caps, on the axis,
    /// far away, and NaN.
    #[test]
    fn lane_keys_equal_the_scalar_ones() {
        let shapes = [
            Shape::Sphere {
                centre: Vec3::new(0.1, 0.2, -0.05),
                radius: 0.02,
            },
            Shape::Cylinder {
                a: Vec3::new(-0.2, 0.05, 0.0),
                b: Vec3::new(0.25, 0.3, 0.1),
                radius: 0.005,
            },
        ];
        let light = [Light::Point {
            position: Vec3::new(0.0, 1.0, 1.0),
            color: Vec3::ONE,
        }];
        let mut seed = 7u32;
        let mut rnd = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1u32 << 24) as f32
        };
        for shape in shapes {
            let geom = Geom::new(&shape);
            let casters = Casters::new((0, &shape), &light, &[], None).expect("bounded");
            let (centre, axis, len, radius) = match shape {
                Shape::Sphere { centre, radius } => (centre, Vec3::X, 0.0, radius),
                Shape::Cylinder { a, b, radius } => {
                    ((a + b) * 0.5, (b - a).normalize(), (b - a).length(), radius)
                }
                Shape::Plane { .. } => unreachable!(),
            };
            let side = axis.any_orthonormal_vector();
            let mut points = vec![Vec3::NAN, centre, centre + Vec3::splat(1e3)];
            for _ in 0..4000 {
                // Along the axis to past the caps, at a distance from it near
                // the radius plus the margin (a few ulps either side).
                let s = (rnd() * 1.2 - 0.6) * len;
                let around = radius + 1e-5 + (rnd() - 0.5) * 4e-7;
                let turn = glam::Quat::from_axis_angle(axis, rnd() * 6.3) * side;
                points.push(centre + axis * s + turn * around);
            }
            for chunk in points.chunks(8) {
                let mut pts = [centre; 8];
                pts[..chunk.len()].copy_from_slice(chunk);
                let want_clear: u8 =
                    (0..8).fold(0, |m, i| m | u8::from(clear_of(&geom, pts[i])) << i);
                let want_piece: [i32; 8] = std::array::from_fn(|i| casters.piece(pts[i]) as i32);
                let want = (want_clear, want_piece);
                assert_eq!(build(Portable, &geom, &casters, &pts), want, "{pts:?}");
                #[cfg(target_arch = "x86_64")]
                if let Some(a) = crate::simd::Avx2::detect() {
                    assert_eq!(build(a, &geom, &casters, &pts), want, "AVX2 {pts:?}");
                }
            }
        }
    }

    fn build<S: Simd>(s: S, geom: &Geom, casters: &Casters, p: &[Vec3; 8]) -> (u8, [i32; 8]) {
        let at = L3 {
            x: s.load(&p.map(|v| v.x)),
            y: s.load(&p.map(|v| v.y)),
            z: s.load(&p.map(|v| v.z)),
        };
        (
            S::bits(clear_lanes(s, geom, &at)),
            piece_lanes(s, casters.axis(), &at),
        )
    }
}
