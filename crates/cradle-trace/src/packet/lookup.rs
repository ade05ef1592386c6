//! The footprint lookups of a packet's shadow rays from the floor, all lanes at
//! once in lane build `S`: where each lane's start projects from the light onto
//! the plane and which cell of the footprint grid holds it, with the scalar
//! `Footprints::lookup`'s operations in its order, so every lane's answer is
//! the scalar one (`Scan::occluded_lanes` then tests the objects the cell lists).

use super::vec::splat3;
use super::{L3, LANES};
use crate::shadow::{GridView, Lookup};
use crate::simd::Simd;

#[expect(
    clippy::inline_always,
    reason = "inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]
/// `Footprints::lookup` of the lanes' shadow-ray starts `x`, with the same
/// operations: the side of the plane, the projection from the light, the plane
/// coordinates, the grid cell (truncation, as `as usize` of a value in `0..n`).
/// Each lane's answer as a number ([`Lookup::of`]).
#[inline(always)]
pub(super) fn lookup<S: Simd>(s: S, g: &GridView, x: &L3<S::F>) -> [u32; LANES] {
    let k = |v: f32| s.splat(v);
    let n = splat3(s, g.normal);
    // (start - origin).dot(normal) < 0: behind the plane.
    let height = x.sub(&splat3(s, g.origin)).dot(&n);
    let mut unlit = S::lt(height, k(0.0));
    let p = match g.light {
        Ok(l) => {
            // down = (l - x).dot(normal); down <= 1e-6 * height: level with it.
            let lv = splat3(s, l);
            let down = lv.sub(x).dot(&n);
            unlit = unlit | S::le(down, k(1e-6 * g.scale));
            // l + (x - l) * (height / down)
            lv.add(&x.sub(&lv).scale(k(g.scale) / down))
        }
        // x + d * (-(x - origin).dot(normal) / d.dot(normal))
        Err(d) => x.add(&splat3(s, d).scale(-height / k(g.scale))),
    };
    // coords: (p - origin).dot(e1), .dot(e2); then (q - min) * inv_cell.
    let q = p.sub(&splat3(s, g.origin));
    let cx = (q.dot(&splat3(s, g.e1)) - k(g.min.x)) * k(g.inv_cell.x);
    let cy = (q.dot(&splat3(s, g.e2)) - k(g.min.y)) * k(g.inv_cell.y);
    let zero = k(0.0);
    let inside =
        S::le(zero, cx) & S::le(zero, cy) & S::lt(cx, k(g.n.0 as f32)) & S::lt(cy, k(g.n.1 as f32));
    let (unlit, inside) = (S::bits(unlit), S::bits(inside));
    let (ix, iy) = (S::trunc(cx), S::trunc(cy));
    let inside = if g.gridded { inside } else { 0 };
    let mut out = [0; LANES];
    for (i, o) in out.iter_mut().enumerate() {
        // In the grid: 0 <= ix < n.0 and 0 <= iy < n.1 (else not used).
        let cell = (iy[i] as u32)
            .wrapping_mul(g.n.0 as u32)
            .wrapping_add(ix[i] as u32);
        let placed = if inside >> i & 1 != 0 {
            cell
        } else {
            Lookup::ALWAYS
        };
        *o = if unlit >> i & 1 != 0 {
            Lookup::UNLIT
        } else {
            placed
        };
    }
    out
}
