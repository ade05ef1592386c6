//! The packet's shading over the lanes, in lane build `S`: `shade` at depth 0
//! of the floor lanes (their checker, lights, shadow rays by the tile's bits or
//! the footprint cells, and mirror rays through the tile's list), and the
//! lights and shadow rays of what a bounce met (`local_lanes`). Each line
//! mirrors the scalar expression in its comment.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::hits::{box8, plane8, recip};
use super::nearest::Nearest;
use super::rays::{Bounce, Met};
use super::{Floor, L3, LANES, Packet, Surface, f8, lanes, splat3};
use crate::material::{BAILOUT, base_color, highlight, powi};
use crate::scene::{Light, Material, Shape};
use crate::simd::Simd;
use glam::Vec3;

/// Below this in magnitude, floored values, the sum of two (below 2^23) and
/// its parity are exact in `f32`.
const SMALL: f32 = 4_194_304.0; // 2^22

impl Packet<'_, '_> {
    /// `shade` at depth 0 of the floor lanes `on` (a bit each) at `hit`: what
    /// [`Self::local_lanes`] gives, blended with what the mirror rays bring.
    #[inline(always)]
    pub(super) fn shade_lanes<S: Simd>(
        &self,
        s: S,
        floor: &Floor<'_>,
        (x0, y): (u32, u32),
        on: u8,
        hit: &Surface<S::F>,
    ) -> L3<S::F> {
        // Camera rays met the floor: their shadow rays are free.
        let mut color = self.local_lanes(s, Met::Floor(floor), (on, 0xFF), hit);
        let r = floor.material.reflective;
        // weight * r * bound, at weight 1.
        if r > 0.0 && 0 < self.p.scene.max_depth && r * self.bound >= BAILOUT {
            let refl = self.mirrors(s, floor, (x0, y, on), hit, r);
            // color = color * (1.0 - r) + reflected * r
            let k = |v: f32| s.splat(v);
            color = color.scale(k(1.0 - r)).add(&refl.scale(k(r)));
        }
        color
    }

    /// `shade`'s lights of what the lanes `on` met (`met`) at `hit`, before
    /// any reflection: ambient, Lambert and Phong terms, each light's shadow
    /// rays traced over the lanes (free in the lanes of `free`,
    /// [`crate::motion::Record`]).
    #[inline(always)]
    pub(super) fn local_lanes<S: Simd>(
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
        let p = self.p;
        let m = met.material();
        let k = |v: f32| s.splat(v);
        let b = Self::surface_lanes(s, m, point);
        let keys = match met {
            Met::Object {
                object,
                outside,
                plane: false,
                ..
            } => self.caster_keys(s, object, (outside, on), start),
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
            self.note_lanes(s, (traced, free), (start, &to_light), dist);
            let rays = (start, &to_light, dist);
            let blocked = match met {
                Met::Floor(floor) => self.shadows(s, floor, li, rays, want),
                Met::Object {
                    object,
                    plane: true,
                    ..
                } => s.mask(self.occluded_lanes(s, (object, li), (start, &to_light), dist, traced)),
                Met::Object { object, .. } => {
                    s.mask(self.object_shadows(s, (object, li, &keys), rays, traced))
                }
            };
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

    /// The lanes' base colour (`base_color`: a checker on the x-z grid, or
    /// plain). Where both coordinates are small, `floor(x) + floor(z)` and its
    /// parity are exact in `f32`; elsewhere (far away, or NaN) each lane takes
    /// `base_color` itself.
    #[inline(always)]
    pub(super) fn surface_lanes<S: Simd>(s: S, m: &Material, point: &L3<S::F>) -> L3<S::F> {
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

    /// Per lane, whether the shadow ray from `start` towards light `li` is
    /// blocked (lanes facing away, `lambert <= 0`, are not traced): what the
    /// lane's footprint cell lists say ([`Self::occluded_lanes`]).
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
        s.mask(self.occluded_lanes(s, (floor.object, li), (start, to_light), dist, want))
    }

    /// Per lane, where the ray from `origin` along `dir` meets plane object `k`
    /// (`hit_plane`), or infinity for a miss.
    #[inline(always)]
    pub(super) fn plane_hits<S: Simd>(
        &self,
        s: S,
        k: usize,
        origin: &L3<S::F>,
        dir: &L3<S::F>,
    ) -> S::F {
        let Shape::Plane { point, normal } = self.p.scene.objects[k].shape else {
            unreachable!("planes() lists planes")
        };
        plane8(s, (point, normal), origin, dir)
    }

    /// Per lane, the radiance the floor's mirror rays bring back (`reflect` at
    /// depth 1 with weight `r`): the nearest hit among the tile's mirror
    /// candidates, found over the lanes, then traced on over the lanes
    /// ([`Self::bounce`]). A packet whose lanes all meet nothing takes the
    /// background at once.
    #[inline(always)]
    fn mirrors<S: Simd>(
        &self,
        s: S,
        floor: &Floor<'_>,
        (x0, y, on_floor): (u32, u32, u8),
        Surface { d, start, nn, .. }: &Surface<S::F>,
        r: f32,
    ) -> L3<S::F> {
        // dir - 2.0 * dir.dot(n) * n
        let dir = d.sub(&nn.scale(s.splat(2.0) * d.dot(nn)));
        // The nearest of the tile's mirror candidates per lane, as
        // `closest_among` finds it: the candidates in order, each box tested
        // with the nearest hit so far as its limit, a hit taken only where
        // nearer (so the first of equally near ones). Lanes that meet none see
        // the background.
        let mut missed = 0u8;
        let mut found = None;
        if let Some(list) = self.tiles.mirror_at(floor.object, x0, y) {
            let inf = s.splat(f32::INFINITY);
            let inv = recip(s, &dir);
            let mut near = Nearest::before(s, inf);
            // Not the floor itself (`Prepared::closest_among`).
            for &k in list.iter().filter(|&&k| k != floor.object) {
                if matches!(self.p.scene.objects[k].shape, Shape::Plane { .. }) {
                    let t = self.plane_hits(s, k, start, &dir);
                    near.offer(s, s.mask(0xFF), (t, s.splat(0.0)), k);
                    continue;
                }
                let inside = box8(s, &self.p.boxes[k], start, &inv, near.best);
                if S::bits(inside) & on_floor == 0 {
                    continue;
                }
                near.offer_object(s, inside, (self.p.geom(k), k), (start, &dir));
            }
            missed = !S::bits(S::lt(near.best, inf));
            found = Some(near.found(missed));
        }
        if on_floor & !missed == 0 && self.motion.is_none() {
            // Every lane sees the background, and there is nothing to note.
            return splat3(s, self.p.scene.background);
        }
        // `reflect` through the tile's list: the object found above; without
        // one, `closest` (the nearest of all, the same hit).
        let mirror = Bounce {
            origin: *start,
            d: dir,
            depth: 1,
            weight: s.splat(r),
            // Mirror rays of camera rays off the floor: free.
            free: 0xFF,
            from: s.splat(floor.object as f32),
        };
        self.bounce(s, &mirror, on_floor, found)
    }
}
