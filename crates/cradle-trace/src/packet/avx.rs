//! The lanes' box, sphere and cylinder tests written with AVX instructions
//! (the compiler's own vectorization of the per-lane code keeps much of it
//! scalar). Each is the scalar test's operations in the scalar order, one IEEE
//! instruction per operation: `minps(a, b)`/`maxps(a, b)` are glam's `a < b ? a
//! : b` and `a > b ? a : b`; `-x` flips the sign bit; comparisons are ordered
//! (false for NaN) except `!(x < 0)`, which is true for NaN, as in the scalar
//! code. So every lane's answer is the scalar one. Answers are bit masks, bit
//! `i` for lane `i`.

use super::{F8, LANES, V8};
use crate::geometry::{Aabb, Cylinder, T_MIN};
use crate::shadow::{GridView, Lookup};
use crate::simd::load8 as load;
use glam::Vec3;
use std::arch::x86_64::{
    __m256, _CMP_GE_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _CMP_NLT_UQ, _mm256_add_ps,
    _mm256_and_ps, _mm256_andnot_ps, _mm256_blendv_ps, _mm256_cmp_ps, _mm256_cvttps_epi32,
    _mm256_div_ps, _mm256_max_ps, _mm256_min_ps, _mm256_movemask_ps, _mm256_mul_ps, _mm256_or_ps,
    _mm256_set1_ps, _mm256_sqrt_ps, _mm256_storeu_si256, _mm256_sub_ps, _mm256_xor_ps,
};

/// Three lane registers: a vector per lane.
#[derive(Clone, Copy)]
struct R3 {
    x: __m256,
    y: __m256,
    z: __m256,
}

#[target_feature(enable = "avx2")]
fn r3(v: &V8) -> R3 {
    R3 {
        x: load(&v.x),
        y: load(&v.y),
        z: load(&v.z),
    }
}

/// `(a.x * b.x) + (a.y * b.y) + (a.z * b.z)`.
#[target_feature(enable = "avx2")]
fn dot(a: R3, b: R3) -> __m256 {
    _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(a.x, b.x), _mm256_mul_ps(a.y, b.y)),
        _mm256_mul_ps(a.z, b.z),
    )
}

/// `v - c` for a vector `c` the same in every lane.
#[target_feature(enable = "avx2")]
fn sub_c(v: R3, c: Vec3) -> R3 {
    R3 {
        x: _mm256_sub_ps(v.x, _mm256_set1_ps(c.x)),
        y: _mm256_sub_ps(v.y, _mm256_set1_ps(c.y)),
        z: _mm256_sub_ps(v.z, _mm256_set1_ps(c.z)),
    }
}

/// `a - b * k` per component.
#[target_feature(enable = "avx2")]
fn sub_scaled(a: R3, b: R3, k: __m256) -> R3 {
    R3 {
        x: _mm256_sub_ps(a.x, _mm256_mul_ps(b.x, k)),
        y: _mm256_sub_ps(a.y, _mm256_mul_ps(b.y, k)),
        z: _mm256_sub_ps(a.z, _mm256_mul_ps(b.z, k)),
    }
}

#[target_feature(enable = "avx2")]
fn neg(x: __m256) -> __m256 {
    _mm256_xor_ps(x, _mm256_set1_ps(-0.0))
}

#[target_feature(enable = "avx2")]
fn mask(x: __m256) -> u8 {
    // Eight sign bits: a value below 256.
    _mm256_movemask_ps(x) as u8
}

/// `Aabb::hit` of the lanes' rays (origins `o`, inverse directions `inv`).
#[target_feature(enable = "avx2")]
pub(super) fn aabb(b: &Aabb, o: &V8, inv: &V8, t_max: &F8) -> u8 {
    let slab = |lo: f32, hi: f32, o: &F8, inv: &F8| {
        let (o, inv) = (load(o), load(inv));
        let t1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(lo), o), inv);
        let t2 = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(hi), o), inv);
        (_mm256_min_ps(t1, t2), _mm256_max_ps(t1, t2))
    };
    let (lx, hx) = slab(b.min.x, b.max.x, &o.x, &inv.x);
    let (ly, hy) = slab(b.min.y, b.max.y, &o.y, &inv.y);
    let (lz, hz) = slab(b.min.z, b.max.z, &o.z, &inv.z);
    let near = _mm256_max_ps(
        _mm256_max_ps(lx, _mm256_max_ps(ly, lz)),
        _mm256_set1_ps(T_MIN),
    );
    let far = _mm256_min_ps(_mm256_min_ps(hx, _mm256_min_ps(hy, hz)), load(t_max));
    mask(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far))
}

/// `hit_sphere`'s nearest hit below `t_max`, per lane.
#[target_feature(enable = "avx2")]
pub(super) fn sphere(centre: Vec3, radius: f32, o: &V8, d: &V8, t_max: &F8) -> u8 {
    let d = r3(d);
    let oc = sub_c(r3(o), centre);
    let b = dot(oc, d);
    let f = sub_scaled(oc, d, b);
    let disc = _mm256_sub_ps(_mm256_set1_ps(radius * radius), dot(f, f));
    let s = _mm256_sqrt_ps(disc);
    let (t0, t1) = (_mm256_sub_ps(neg(b), s), _mm256_add_ps(neg(b), s));
    let t_min = _mm256_set1_ps(T_MIN);
    let first = _mm256_blendv_ps(t1, t0, _mm256_cmp_ps::<_CMP_GT_OQ>(t0, t_min));
    let ok = _mm256_and_ps(
        _mm256_cmp_ps::<_CMP_NLT_UQ>(disc, _mm256_set1_ps(0.0)),
        _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_GT_OQ>(first, t_min),
            _mm256_cmp_ps::<_CMP_LT_OQ>(first, load(t_max)),
        ),
    );
    mask(ok)
}

/// `Cylinder::hit`'s nearest hit below `t_max`, per lane. "No hit yet" is
/// +inf, which takes and drops the same roots as the scalar `None` (a root of
/// +inf could never be below `t_max`).
#[target_feature(enable = "avx2")]
pub(super) fn cylinder(c: &Cylinder, o: &V8, d: &V8, t_max: &F8) -> u8 {
    let (a, b, u, len, radius) = c.parts();
    let (o, d) = (r3(o), r3(d));
    let uu = R3 {
        x: _mm256_set1_ps(u.x),
        y: _mm256_set1_ps(u.y),
        z: _mm256_set1_ps(u.z),
    };
    let ao = sub_c(o, a);
    let du = dot(d, uu);
    let ou = dot(ao, uu);
    // dir - u * du, ao - u * ou: (u.x * du) is (du * u.x), the same product.
    let dp = sub_scaled(d, uu, du);
    let op = sub_scaled(ao, uu, ou);
    let qa = dot(dp, dp);
    let qb = dot(op, dp);
    let r2 = _mm256_set1_ps(radius * radius);
    let t_min = _mm256_set1_ps(T_MIN);
    let zero = _mm256_set1_ps(0.0);
    let body = _mm256_cmp_ps::<_CMP_GT_OQ>(qa, _mm256_set1_ps(1e-12));
    let f = sub_scaled(op, dp, _mm256_div_ps(qb, qa));
    let disc = _mm256_mul_ps(qa, _mm256_sub_ps(r2, dot(f, f)));
    let miss_all = _mm256_and_ps(body, _mm256_cmp_ps::<_CMP_LT_OQ>(disc, zero));
    let s = _mm256_sqrt_ps(disc);
    let mut best = _mm256_set1_ps(f32::INFINITY);
    let nearer = |best: __m256, t: __m256| {
        _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_GT_OQ>(t, t_min),
            _mm256_cmp_ps::<_CMP_LT_OQ>(t, best),
        )
    };
    for root in [_mm256_sub_ps(neg(qb), s), _mm256_add_ps(neg(qb), s)] {
        let t = _mm256_div_ps(root, qa);
        let along = _mm256_add_ps(ou, _mm256_mul_ps(t, du));
        let inside = _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_LE_OQ>(zero, along),
            _mm256_cmp_ps::<_CMP_LE_OQ>(along, _mm256_set1_ps(len)),
        );
        let take = _mm256_and_ps(_mm256_and_ps(body, inside), nearer(best, t));
        best = _mm256_blendv_ps(best, t, take);
    }
    // |du| > 1e-12: the sign bit cleared.
    let abs_du = _mm256_andnot_ps(_mm256_set1_ps(-0.0), du);
    let caps = _mm256_cmp_ps::<_CMP_GT_OQ>(abs_du, _mm256_set1_ps(1e-12));
    for (end, along) in [(a, 0.0), (b, len)] {
        let t = _mm256_div_ps(_mm256_sub_ps(_mm256_set1_ps(along), ou), du);
        // ray.at(t) - end: (origin + dir * t) - end.
        let p = R3 {
            x: _mm256_add_ps(o.x, _mm256_mul_ps(d.x, t)),
            y: _mm256_add_ps(o.y, _mm256_mul_ps(d.y, t)),
            z: _mm256_add_ps(o.z, _mm256_mul_ps(d.z, t)),
        };
        let p = sub_c(p, end);
        let within = _mm256_cmp_ps::<_CMP_LE_OQ>(dot(p, p), r2);
        let take = _mm256_and_ps(_mm256_and_ps(caps, within), nearer(best, t));
        best = _mm256_blendv_ps(best, t, take);
    }
    let hit = _mm256_andnot_ps(miss_all, _mm256_cmp_ps::<_CMP_LT_OQ>(best, load(t_max)));
    mask(hit)
}

/// `Footprints::lookup` of the lanes' shadow-ray starts `x`, with the same
/// operations: the side of the plane, the projection from the light, the plane
/// coordinates, the grid cell (truncation, as `as usize` of a value in
/// `0..n`).
#[target_feature(enable = "avx2")]
pub(super) fn lookup(g: &GridView, x: &V8) -> [Lookup; LANES] {
    let x = r3(x);
    let splat = |v: Vec3| R3 {
        x: _mm256_set1_ps(v.x),
        y: _mm256_set1_ps(v.y),
        z: _mm256_set1_ps(v.z),
    };
    let n = splat(g.normal);
    let zero = _mm256_set1_ps(0.0);
    // (start - origin).dot(normal) < 0: behind the plane.
    let mut unlit = _mm256_cmp_ps::<_CMP_LT_OQ>(dot(sub_c(x, g.origin), n), zero);
    let p = match g.light {
        Ok(l) => {
            // down = (l - x).dot(normal); down <= 1e-6 * height: level with it.
            let lv = splat(l);
            let down = dot(
                R3 {
                    x: _mm256_sub_ps(lv.x, x.x),
                    y: _mm256_sub_ps(lv.y, x.y),
                    z: _mm256_sub_ps(lv.z, x.z),
                },
                n,
            );
            let level = _mm256_cmp_ps::<_CMP_LE_OQ>(down, _mm256_set1_ps(1e-6 * g.scale));
            unlit = _mm256_or_ps(unlit, level);
            // l + (x - l) * (height / down)
            let s = _mm256_div_ps(_mm256_set1_ps(g.scale), down);
            let xl = sub_c(x, l);
            R3 {
                x: _mm256_add_ps(lv.x, _mm256_mul_ps(xl.x, s)),
                y: _mm256_add_ps(lv.y, _mm256_mul_ps(xl.y, s)),
                z: _mm256_add_ps(lv.z, _mm256_mul_ps(xl.z, s)),
            }
        }
        Err(d) => {
            // x + d * (-(x - origin).dot(normal) / d.dot(normal))
            let s = _mm256_div_ps(neg(dot(sub_c(x, g.origin), n)), _mm256_set1_ps(g.scale));
            let dv = splat(d);
            R3 {
                x: _mm256_add_ps(x.x, _mm256_mul_ps(dv.x, s)),
                y: _mm256_add_ps(x.y, _mm256_mul_ps(dv.y, s)),
                z: _mm256_add_ps(x.z, _mm256_mul_ps(dv.z, s)),
            }
        }
    };
    // coords: (p - origin).dot(e1), .dot(e2); then (q - min) * inv_cell.
    let q = sub_c(p, g.origin);
    let (qx, qy) = (dot(q, splat(g.e1)), dot(q, splat(g.e2)));
    let cx = _mm256_mul_ps(
        _mm256_sub_ps(qx, _mm256_set1_ps(g.min.x)),
        _mm256_set1_ps(g.inv_cell.x),
    );
    let cy = _mm256_mul_ps(
        _mm256_sub_ps(qy, _mm256_set1_ps(g.min.y)),
        _mm256_set1_ps(g.inv_cell.y),
    );
    let inside = _mm256_and_ps(
        _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_GE_OQ>(cx, zero),
            _mm256_cmp_ps::<_CMP_GE_OQ>(cy, zero),
        ),
        _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_LT_OQ>(cx, _mm256_set1_ps(g.n.0 as f32)),
            _mm256_cmp_ps::<_CMP_LT_OQ>(cy, _mm256_set1_ps(g.n.1 as f32)),
        ),
    );
    let (unlit, inside) = (mask(unlit), mask(inside));
    let (mut ix, mut iy) = ([0i32; LANES], [0i32; LANES]);
    // SAFETY: stores of eight i32 into arrays of eight i32.
    #[expect(unsafe_code, reason = "stores into arrays, in bounds by their type")]
    unsafe {
        _mm256_storeu_si256(ix.as_mut_ptr().cast(), _mm256_cvttps_epi32(cx));
        _mm256_storeu_si256(iy.as_mut_ptr().cast(), _mm256_cvttps_epi32(cy));
    }
    super::lanes(|i| {
        if unlit >> i & 1 != 0 {
            Lookup::Unlit
        } else if !g.gridded || inside >> i & 1 == 0 {
            Lookup::Always
        } else {
            // In the grid: 0 <= ix < n.0 and 0 <= iy < n.1.
            Lookup::Cell(iy[i] as usize * g.n.0 + ix[i] as usize)
        }
    })
}
