//! Shadow rays of a packet's floor lanes, all lanes at once: what
//! `Prepared::occluded_by` answers for each lane's ray (the planes, the group
//! box, then the objects the lane's footprint cell lists, each through its box),
//! with every box, sphere and cylinder test run over the eight lanes. Each lane
//! computes the scalar test's operations in the scalar order (`Aabb::hit`,
//! `hit_sphere`, `Cylinder::hit`; glam's dot is `(x*x' + y*y') + z*z'`), and an
//! "any hit" answer does not depend on the order the objects are tested in, so
//! every lane's answer is the scalar one.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::{F8, LANES, Packet, V8, f8, load3};
use crate::geometry::{Aabb, T_MIN};
use crate::prepared::Geom;
use crate::shadow::Lookup;
use crate::simd::{Portable, Simd};
use glam::Vec3;

pub(super) type B8 = [bool; LANES];

/// `a.dot(b)` per lane, for lane vectors: `(a.x * b.x) + (a.y * b.y) + (a.z * b.z)`.
#[inline(always)]
fn dot8(a: &V8, b: &V8) -> F8 {
    f8(|i| (a.x[i] * b.x[i]) + (a.y[i] * b.y[i]) + (a.z[i] * b.z[i]))
}

/// `origin - c` per lane.
#[inline(always)]
fn sub8(o: &V8, c: Vec3) -> V8 {
    V8 {
        x: f8(|i| o.x[i] - c.x),
        y: f8(|i| o.y[i] - c.y),
        z: f8(|i| o.z[i] - c.z),
    }
}

/// A lane mask as booleans.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn bits(m: u8) -> B8 {
    std::array::from_fn(|i| m >> i & 1 != 0)
}

/// `Aabb::hit` per lane: glam's vector `min`/`max` pick `a < b ? a : b` and
/// `a > b ? a : b`, `max_element` is `max(x, max(y, z))`, then `f32::max(T_MIN)`
/// and `f32::min(t_max)`.
#[inline(always)]
pub(super) fn box8(b: &Aabb, o: &V8, inv: &V8, t_max: &F8) -> B8 {
    #[cfg(target_arch = "x86_64")]
    if crate::simd::avx2() {
        // SAFETY: the CPU has AVX2, checked just above.
        #[expect(unsafe_code, reason = "the run-time dispatch to the AVX2 build")]
        return bits(unsafe { super::avx::aabb(b, o, inv, t_max) });
    }
    let mn = |a: f32, b: f32| if a < b { a } else { b };
    let mx = |a: f32, b: f32| if a > b { a } else { b };
    let slab = |lo: f32, hi: f32, o: &F8, inv: &F8| {
        let t1 = f8(|i| (lo - o[i]) * inv[i]);
        let t2 = f8(|i| (hi - o[i]) * inv[i]);
        (f8(|i| mn(t1[i], t2[i])), f8(|i| mx(t1[i], t2[i])))
    };
    let (lx, hx) = slab(b.min.x, b.max.x, &o.x, &inv.x);
    let (ly, hy) = slab(b.min.y, b.max.y, &o.y, &inv.y);
    let (lz, hz) = slab(b.min.z, b.max.z, &o.z, &inv.z);
    let near = f8(|i| mx(lx[i], mx(ly[i], lz[i])).max(T_MIN));
    let far = f8(|i| mn(hx[i], mn(hy[i], hz[i])).min(t_max[i]));
    std::array::from_fn(|i| near[i] <= far[i])
}

/// Per lane, whether object `g` meets the ray before `t_max` (its nearest hit
/// beyond `T_MIN`, as `hit_sphere` or `Cylinder::hit` finds it, is below
/// `t_max`); planes are tested elsewhere.
#[inline(always)]
pub(super) fn blocks8(g: &Geom, o: &V8, d: &V8, t_max: &F8) -> B8 {
    #[cfg(target_arch = "x86_64")]
    if crate::simd::avx2() {
        // SAFETY: the CPU has AVX2, checked just above.
        #[expect(unsafe_code, reason = "the run-time dispatch to the AVX2 build")]
        return bits(match *g {
            Geom::Sphere { centre, radius } => unsafe {
                super::avx::sphere(centre, radius, o, d, t_max)
            },
            Geom::Cylinder(ref c) => unsafe { super::avx::cylinder(c, o, d, t_max) },
            Geom::Plane { .. } => 0,
        });
    }
    match *g {
        Geom::Sphere { centre, radius } => {
            // hit_sphere: oc, b = oc.dot(dir), f = oc - dir * b, disc = r*r - |f|^2,
            // the first of -b - s, -b + s beyond T_MIN.
            let oc = sub8(o, centre);
            let b = dot8(&oc, d);
            let f = V8 {
                x: f8(|i| oc.x[i] - d.x[i] * b[i]),
                y: f8(|i| oc.y[i] - d.y[i] * b[i]),
                z: f8(|i| oc.z[i] - d.z[i] * b[i]),
            };
            let ff = dot8(&f, &f);
            std::array::from_fn(|i| {
                let disc = radius * radius - ff[i];
                if disc < 0.0 {
                    return false;
                }
                let s = disc.sqrt();
                let (t0, t1) = (-b[i] - s, -b[i] + s);
                let t = if t0 > T_MIN {
                    t0
                } else if t1 > T_MIN {
                    t1
                } else {
                    return false;
                };
                t < t_max[i]
            })
        }
        Geom::Cylinder(c) => {
            let (a, b, u, len, radius) = c.parts();
            let ao = sub8(o, a);
            let du = f8(|i| (d.x[i] * u.x) + (d.y[i] * u.y) + (d.z[i] * u.z));
            let ou = f8(|i| (ao.x[i] * u.x) + (ao.y[i] * u.y) + (ao.z[i] * u.z));
            let dp = V8 {
                x: f8(|i| d.x[i] - u.x * du[i]),
                y: f8(|i| d.y[i] - u.y * du[i]),
                z: f8(|i| d.z[i] - u.z * du[i]),
            };
            let op = V8 {
                x: f8(|i| ao.x[i] - u.x * ou[i]),
                y: f8(|i| ao.y[i] - u.y * ou[i]),
                z: f8(|i| ao.z[i] - u.z * ou[i]),
            };
            let qa = dot8(&dp, &dp);
            let qb = dot8(&op, &dp);
            std::array::from_fn(|i| {
                let mut best: Option<f32> = None;
                let nearer = |best: Option<f32>, t: f32| t > T_MIN && best.is_none_or(|bt| t < bt);
                if qa[i] > 1e-12 {
                    let k = qb[i] / qa[i];
                    let f = Vec3::new(
                        op.x[i] - dp.x[i] * k,
                        op.y[i] - dp.y[i] * k,
                        op.z[i] - dp.z[i] * k,
                    );
                    let disc = qa[i] * (radius * radius - f.length_squared());
                    if disc < 0.0 {
                        return false;
                    }
                    let s = disc.sqrt();
                    for t in [(-qb[i] - s) / qa[i], (-qb[i] + s) / qa[i]] {
                        let along = ou[i] + t * du[i];
                        if (0.0..=len).contains(&along) && nearer(best, t) {
                            best = Some(t);
                        }
                    }
                }
                if du[i].abs() > 1e-12 {
                    let (oi, di) = (o.lane(i), d.lane(i));
                    for (end, along) in [(a, 0.0), (b, len)] {
                        let t = (along - ou[i]) / du[i];
                        if nearer(best, t)
                            && ((oi + di * t) - end).length_squared() <= radius * radius
                        {
                            best = Some(t);
                        }
                    }
                }
                best.is_some_and(|t| t < t_max[i])
            })
        }
        Geom::Plane { .. } => [false; LANES],
    }
}

impl Packet<'_, '_> {
    /// Per lane, whether any of the objects `others` meets its primary ray
    /// (from the eye along `d`) before `t`: `closest_among`'s box test with `t`
    /// as the limit, then its hit test.
    #[inline(always)]
    pub(super) fn nearer_than(&self, others: &[usize], d: &V8, t: &F8) -> B8 {
        let o = self.cam.origin;
        let eye = V8 {
            x: [o.x; LANES],
            y: [o.y; LANES],
            z: [o.z; LANES],
        };
        let inv = V8 {
            x: f8(|i| 1.0 / d.x[i]),
            y: f8(|i| 1.0 / d.y[i]),
            z: f8(|i| 1.0 / d.z[i]),
        };
        let mut front = [false; LANES];
        for &k in others {
            let inside = box8(&self.p.boxes[k], &eye, &inv, t);
            if inside.contains(&true) {
                let hit = blocks8(self.p.geom(k), &eye, d, t);
                for i in 0..LANES {
                    front[i] |= inside[i] && hit[i];
                }
            }
        }
        front
    }

    /// Per lane, `Prepared::occluded_by(ray, dist, footprints)` for the shadow
    /// rays from `start` along `dir` towards light `li` of floor object `plane`,
    /// for the lanes in `want` (the others answer false).
    #[inline(always)]
    pub(super) fn occluded_lanes(
        &self,
        (plane, li): (usize, usize),
        start: &V8,
        dir: &V8,
        dist: &F8,
        want: B8,
    ) -> B8 {
        let p = self.p;
        let mut out = [false; LANES];
        // The planes first: a hit before dist on any of them.
        for &k in p.planes() {
            let t = Portable::store(self.plane_hits(
                Portable,
                k,
                &load3(Portable, start),
                &load3(Portable, dir),
            ));
            for i in 0..LANES {
                out[i] |= want[i] && t[i] < dist[i];
            }
        }
        // inv = dir.recip(); the group box.
        let inv = V8 {
            x: f8(|i| 1.0 / dir.x[i]),
            y: f8(|i| 1.0 / dir.y[i]),
            z: f8(|i| 1.0 / dir.z[i]),
        };
        let group = box8(&p.group, start, &inv, dist);
        let mut todo: B8 = std::array::from_fn(|i| want[i] && !out[i] && group[i]);
        let fp = p.footprints(plane, li);
        // Lane by lane, where its footprint cell is (or no grid: every object);
        // lanes with the same lists are tested together.
        let at: [Lookup; LANES] = match fp {
            None => [Lookup::Unlit; LANES],
            #[cfg(target_arch = "x86_64")]
            Some(f) if crate::simd::avx2() => {
                // SAFETY: the CPU has AVX2, checked just above.
                #[expect(unsafe_code, reason = "the run-time dispatch to the AVX2 build")]
                unsafe {
                    super::avx::lookup(&f.view(), start)
                }
            }
            Some(f) => std::array::from_fn(|i| f.lookup(start.lane(i))),
        };
        while let Some(first) = (0..LANES).find(|&i| todo[i]) {
            let group: B8 = std::array::from_fn(|i| todo[i] && at[i] == at[first]);
            let mut test = |k: usize| {
                let live: B8 = std::array::from_fn(|i| group[i] && !out[i]);
                if !live.contains(&true) {
                    return;
                }
                let inside = box8(&p.boxes[k], start, &inv, dist);
                if !(0..LANES).any(|i| live[i] && inside[i]) {
                    return;
                }
                let hit = blocks8(p.geom(k), start, dir, dist);
                for i in 0..LANES {
                    out[i] |= live[i] && inside[i] && hit[i];
                }
            };
            match fp.and_then(|f| f.list(at[first])) {
                Some((cell, always)) => cell.iter().chain(always).for_each(|&k| test(k)),
                None => p.bounded.iter().for_each(|&(k, _)| test(k)),
            }
            for i in 0..LANES {
                todo[i] &= !group[i];
            }
        }
        out
    }
}
