//! The lights of what the lanes met, in lane build `S` ([`Lights`]): `shade`'s
//! terms before any reflection (ambient, Lambert, Phong), the base colour of
//! the surface (a checker or plain), and each light's shadow rays, by the
//! footprint cells from a plane, by the casters from a bounded object. Each
//! line mirrors the scalar expression in its comment.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::LANES;
use super::notes::LaneNotes;
use super::rays::{Floor, Met};
use super::scan::Scan;
use super::vec::{L3, Surface, f8, lanes, splat3};
use crate::material::{base_color, highlight, powi};
use crate::scene::{Light, Material};
use crate::simd::Simd;
use glam::Vec3;

/// Below this in magnitude, floored values, the sum of two (below 2^23) and
/// its parity are exact in `f32`.
const SMALL: f32 = 4_194_304.0; // 2^22

/// The lights of a surface: the scene's queries for its shadow rays, and
/// the notes the rays leave in a tracked frame.
#[derive(Clone, Copy)]
pub(super) struct Lights<'a, 'p, const T: bool> {
    pub(super) scan: Scan<'a, 'p, T>,
    pub(super) notes: &'a LaneNotes,
}

impl<const T: bool> Lights<'_, '_, T> {
    /// `shade`'s lights of what the lanes `on` met (`met`) at `hit`, before
    /// any reflection: ambient, Lambert and Phong terms, each light's shadow
    /// rays traced over the lanes (free in the lanes of `free`,
    /// [`crate::motion::Record`]).
    #[inline(always)]
    pub(super) fn local<S: Simd>(
        &self,
        s: S,
        met: Met<'_>,
        (on, free): (u8, u8),
        hit: &Surface<S::F>,
    ) -> L3<S::F> {
        let Surface {
            d,
            point,
            start,
            nn,
        } = hit;
        let p = self.scan.p;
        let m = met.material();
        let k = |v: f32| s.splat(v);
        let b = base_lanes(s, m, point);
        let keys = match met {
            Met::Object {
                object,
                outside,
                plane: false,
                ..
            } => self.scan.caster_keys(s, object, (outside, on), start),
            _ => [(0, false); LANES],
        };
        let mut color = splat3(s, Vec3::ZERO);
        for (li, light) in p.scene.lights.iter().enumerate() {
            let (to_light, dist, lc) = match *light {
                Light::Ambient { color: c } => {
                    // color += base * c
                    color = color.add(&b.mul(&splat3(s, c)));
                    continue;
                }
                Light::Point { position, color: c } => {
                    // d = position - point; len = d.length(); (d / len, len)
                    let dv = splat3(s, position).sub(point);
                    let len = S::sqrt(dv.dot(&dv));
                    (dv.div(len), len, c)
                }
                Light::Directional {
                    direction,
                    color: c,
                } => (splat3(s, -direction), k(f32::INFINITY), c),
            };
            // lambert = n.dot(to_light)
            let lambert = nn.dot(&to_light);
            // Lanes not to shade trace no shadow rays.
            let want = S::select(s.mask(on), lambert, k(0.0));
            // !(lambert <= 0): a NaN lambert is traced, as in the scalar code.
            let traced = S::bits(!S::le(want, k(0.0)));
            (self.notes).note::<T, S>(s, (traced, free), (start, &to_light), dist);
            let rays = (start, &to_light, dist);
            let blocked = match met {
                Met::Floor(floor) => self.shadows(s, floor, li, rays, want),
                Met::Object {
                    object,
                    plane: true,
                    ..
                } => s.mask(self.scan.occluded_lanes(
                    s,
                    (object, li),
                    (start, &to_light),
                    dist,
                    traced,
                )),
                Met::Object { object, .. } => {
                    s.mask(
                        self.scan
                            .object_shadows(s, (object, li, &keys), rays, traced),
                    )
                }
            };
            (self.notes).after_shadows::<T>(traced & S::bits(blocked), self.scan.p);
            // Skipped where lambert <= 0 or the light is blocked; else
            // color += base * light_color * lambert.
            let lit = !S::le(lambert, k(0.0)) & !blocked;
            let add = |c: S::F, b: S::F, l: f32| S::select(lit, c + (b * k(l)) * lambert, c);
            color = L3 {
                x: add(color.x, b.x, lc.x),
                y: add(color.y, b.y, lc.y),
                z: add(color.z, b.z, lc.z),
            };
            if let Some(phong) = p.phong(met.object()) {
                // mirrored = 2.0 * lambert * n - to_light; facing = mirrored.dot(-dir)
                let mirrored = nn.scale(k(2.0) * lambert).sub(&to_light);
                let facing = mirrored.dot(&d.neg());
                let shiny = lit & S::lt(k(0.0), facing);
                let on = S::bits(shiny);
                if on != 0 {
                    // color += light_color * highlight(facing, phong): 0 below
                    // `least`; the lanes not kept take the power of 1, so no
                    // lane squares a subnormal number.
                    let pk = if let Some(n) = phong.whole {
                        let kept = shiny & S::le(k(phong.least), facing);
                        let x = S::select(kept, facing, k(1.0));
                        S::select(kept, powi(x, n), k(0.0))
                    } else {
                        let f = S::store(facing);
                        s.load(&f8(|i| {
                            if on >> i & 1 != 0 {
                                highlight(f[i], phong)
                            } else {
                                0.0
                            }
                        }))
                    };
                    let add = |c: S::F, l: f32| S::select(shiny, c + k(l) * pk, c);
                    color = L3 {
                        x: add(color.x, lc.x),
                        y: add(color.y, lc.y),
                        z: add(color.z, lc.z),
                    };
                }
            }
        }
        color
    }

    /// Per lane, whether the shadow ray from `start` towards light `li` is
    /// blocked (lanes facing away, `lambert <= 0`, are not traced): what the
    /// lane's footprint cell lists say ([`Scan::occluded_lanes`]).
    #[inline(always)]
    fn shadows<S: Simd>(
        &self,
        s: S,
        floor: &Floor<'_>,
        li: usize,
        (start, to_light, dist): (&L3<S::F>, &L3<S::F>, S::F),
        lambert: S::F,
    ) -> S::M {
        let want = S::bits(S::lt(s.splat(0.0), lambert));
        s.mask(
            self.scan
                .occluded_lanes(s, (floor.object, li), (start, to_light), dist, want),
        )
    }
}

/// The lanes' base colour (`base_color`: a checker on the x-z grid, or
/// plain). Where both coordinates are small, `floor(x) + floor(z)` and its
/// parity are exact in `f32`; elsewhere (far away, or NaN) each lane takes
/// `base_color` itself.
#[inline(always)]
pub(super) fn base_lanes<S: Simd>(s: S, m: &Material, point: &L3<S::F>) -> L3<S::F> {
    let Some((other, size)) = m.checker else {
        return splat3(s, m.color);
    };
    let k = |v: f32| s.splat(v);
    // cell = floor_i64(point.x / size) + floor_i64(point.z / size)
    let (qx, qz) = (point.x / k(size), point.z / k(size));
    let small = S::lt(S::abs(qx), k(SMALL)) & S::lt(S::abs(qz), k(SMALL));
    if S::bits(small) != 0xFF {
        let (px, pz) = (S::store(point.x), S::store(point.z));
        let base: [Vec3; LANES] = lanes(|i| base_color(m, Vec3::new(px[i], 0.0, pz[i])));
        return L3 {
            x: s.load(&f8(|i| base[i].x)),
            y: s.load(&f8(|i| base[i].y)),
            z: s.load(&f8(|i| base[i].z)),
        };
    }
    let cell = S::floor_small(qx) + S::floor_small(qz);
    // cell.rem_euclid(2) == 0: even cells are the material's colour.
    let odd = S::lt(k(0.0), cell - k(2.0) * S::floor_small(cell * k(0.5)));
    L3 {
        x: S::select(odd, k(other.x), k(m.color.x)),
        y: S::select(odd, k(other.y), k(m.color.y)),
        z: S::select(odd, k(other.z), k(m.color.z)),
    }
}
