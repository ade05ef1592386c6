//! The packet's shading, lane by lane (`shade` at depth 0 for floor hits): the
//! lights, the shadow tests of a tile no caster can shadow, and the mirror rays of
//! a tile with only planes to meet, for all lanes at once; the rest through the
//! scalar queries, one lane at a time. Each line mirrors the scalar expression in
//! its comment.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::occlusion::{blocks8, box8};
use super::{F8, Floor, LANES, Packet, V8, f8, lanes};
use crate::geometry::{Ray, T_MIN};
use crate::motion::Motion;
use crate::scene::{Light, Shape};
use crate::shade::{BAILOUT, floor_i64, reflect};
use crate::tiles::Tiles;
use glam::Vec3;

impl Packet<'_, '_> {
    /// `shade` of floor hits at depth 0, lane by lane: `d` the rays' directions,
    /// `point` their hits, `start` the secondary rays' origins, `nv(i)` the normal.
    #[inline(always)]
    pub(super) fn shade_lanes(
        &self,
        floor: &Floor<'_>,
        (x0, y): (u32, u32),
        on_floor: [bool; LANES],
        (d, point, start): (&V8, &V8, &V8),
        nv: &impl Fn(usize) -> Vec3,
    ) -> V8 {
        let p = self.p;
        let m = floor.material;
        let tile = Some((self.tiles, x0, y));
        let (b, nn) = Self::surface_lanes(floor, point, nv);
        let mut color = V8 {
            x: [0.0; LANES],
            y: [0.0; LANES],
            z: [0.0; LANES],
        };
        for (li, light) in p.scene.lights.iter().enumerate() {
            let (to_light, dist, lc) = match *light {
                Light::Ambient { color: c } => {
                    // color += base * c
                    color.x = f8(|i| color.x[i] + b.x[i] * c.x);
                    color.y = f8(|i| color.y[i] + b.y[i] * c.y);
                    color.z = f8(|i| color.z[i] + b.z[i] * c.z);
                    continue;
                }
                Light::Point { position, color: c } => {
                    // d = position - point; len = d.length(); (d / len, len)
                    let dv = V8 {
                        x: f8(|i| position.x - point.x[i]),
                        y: f8(|i| position.y - point.y[i]),
                        z: f8(|i| position.z - point.z[i]),
                    };
                    let len = f8(|i| {
                        ((dv.x[i] * dv.x[i]) + (dv.y[i] * dv.y[i]) + (dv.z[i] * dv.z[i])).sqrt()
                    });
                    let tl = V8 {
                        x: f8(|i| dv.x[i] / len[i]),
                        y: f8(|i| dv.y[i] / len[i]),
                        z: f8(|i| dv.z[i] / len[i]),
                    };
                    (tl, len, c)
                }
                Light::Directional {
                    direction,
                    color: c,
                } => {
                    let tl = -direction;
                    let tl = V8 {
                        x: [tl.x; LANES],
                        y: [tl.y; LANES],
                        z: [tl.z; LANES],
                    };
                    (tl, [f32::INFINITY; LANES], c)
                }
            };
            // lambert = n.dot(to_light)
            let lambert = f8(|i| {
                (nn.x[i] * to_light.x[i]) + (nn.y[i] * to_light.y[i]) + (nn.z[i] * to_light.z[i])
            });
            // Lanes off the floor are the scalar path's: no shadow rays for them.
            let want = f8(|i| if on_floor[i] { lambert[i] } else { 0.0 });
            if self.motion.is_some() {
                self.note_shadows(&want, start, &to_light, &dist);
            }
            let blocked = self.shadows(floor, (x0, y, li), start, &to_light, &dist, &want);
            // Skipped where lambert <= 0 or the light is blocked; else
            // color += base * light_color * lambert.
            // !(lambert <= 0): a NaN lambert is not skipped.
            let lit: [bool; LANES] =
                lanes(|i| (lambert[i] > 0.0 || lambert[i].is_nan()) && !blocked[i]);
            let add = |c: &F8, b: &F8, l: f32| {
                f8(|i| {
                    if lit[i] {
                        c[i] + (b[i] * l) * lambert[i]
                    } else {
                        c[i]
                    }
                })
            };
            color = V8 {
                x: add(&color.x, &b.x, lc.x),
                y: add(&color.y, &b.y, lc.y),
                z: add(&color.z, &b.z, lc.z),
            };
            if let Some(exponent) = m.specular {
                // mirrored = 2.0 * lambert * n - to_light; facing = mirrored.dot(-dir)
                let facing = f8(|i| {
                    let s = 2.0 * lambert[i];
                    let mx = s * nn.x[i] - to_light.x[i];
                    let my = s * nn.y[i] - to_light.y[i];
                    let mz = s * nn.z[i] - to_light.z[i];
                    (mx * -d.x[i]) + (my * -d.y[i]) + (mz * -d.z[i])
                });
                for i in 0..LANES {
                    if lit[i] && facing[i] > 0.0 {
                        let k = facing[i].powf(exponent);
                        color.x[i] += lc.x * k;
                        color.y[i] += lc.y * k;
                        color.z[i] += lc.z * k;
                    }
                }
            }
        }
        let r = m.reflective;
        if r > 0.0 && 0 < p.scene.max_depth && r * self.bound >= BAILOUT {
            let refl = self.mirrors(floor, (x0, y, on_floor), d, start, nv, r, tile);
            // color = color * (1.0 - r) + reflected * r
            for i in 0..LANES {
                color.x[i] = color.x[i] * (1.0 - r) + refl.x[i] * r;
                color.y[i] = color.y[i] * (1.0 - r) + refl.y[i] * r;
                color.z[i] = color.z[i] * (1.0 - r) + refl.z[i] * r;
            }
        }
        color
    }

    /// In a tracked frame, notes the shadow rays the lanes trace (`blocked`
    /// notes each one whose lambert, here `lit`, is not <= 0; lanes off the floor
    /// have 0).
    #[inline(never)]
    fn note_shadows(&self, lit: &F8, start: &V8, to_light: &V8, dist: &F8) {
        for i in (0..LANES).filter(|&i| lit[i] > 0.0 || lit[i].is_nan()) {
            let shadow = Ray {
                origin: start.lane(i),
                dir: to_light.lane(i),
            };
            self.note(i, &shadow, dist[i]);
        }
    }

    /// The lanes' base colour (`base_color`: a checker on the x-z grid, or
    /// plain) and normal.
    #[inline(always)]
    fn surface_lanes(floor: &Floor<'_>, point: &V8, nv: &impl Fn(usize) -> Vec3) -> (V8, V8) {
        let m = floor.material;
        let base: [Vec3; LANES] = lanes(|i| match m.checker {
            Some((other, size)) => {
                let cell = floor_i64(point.x[i] / size) + floor_i64(point.z[i] / size);
                if cell.rem_euclid(2) == 0 {
                    m.color
                } else {
                    other
                }
            }
            None => m.color,
        });
        let b = V8 {
            x: f8(|i| base[i].x),
            y: f8(|i| base[i].y),
            z: f8(|i| base[i].z),
        };
        let nn = V8 {
            x: f8(|i| nv(i).x),
            y: f8(|i| nv(i).y),
            z: f8(|i| nv(i).z),
        };
        (b, nn)
    }

    /// Per lane, whether the shadow ray from `start` towards light `li` is
    /// blocked (lanes facing away, `lambert <= 0`, are not traced): where no
    /// caster can shadow the tile, only the planes are tested; elsewhere what
    /// the lane's footprint cell lists too ([`Self::occluded_lanes`]).
    #[inline(always)]
    fn shadows(
        &self,
        floor: &Floor<'_>,
        (x0, y, li): (u32, u32, usize),
        start: &V8,
        to_light: &V8,
        dist: &F8,
        lambert: &F8,
    ) -> [bool; LANES] {
        if self.tiles.shadow_clear(floor.object, li, x0, y) {
            let mut blocked = [false; LANES];
            for &k in self.p.planes() {
                let hit = self.plane_hits(k, start, to_light);
                for i in 0..LANES {
                    blocked[i] |= hit[i] < dist[i];
                }
            }
            return blocked;
        }
        let want = lanes(|i| lambert[i] > 0.0);
        self.occluded_lanes((floor.object, li), start, to_light, dist, want)
    }

    /// Per lane, where the ray from `origin` along `dir` meets plane object `k`
    /// (`hit_plane`), or infinity for a miss.
    #[inline(always)]
    pub(super) fn plane_hits(&self, k: usize, origin: &V8, dir: &V8) -> F8 {
        let Shape::Plane { point, normal } = self.p.scene.objects[k].shape else {
            unreachable!("planes() lists planes")
        };
        // denom = dir.dot(normal); t = (point - origin).dot(normal) / denom
        let denom = dir.dot(normal);
        f8(|i| {
            let t = (((point.x - origin.x[i]) * normal.x)
                + ((point.y - origin.y[i]) * normal.y)
                + ((point.z - origin.z[i]) * normal.z))
                / denom[i];
            if denom[i].abs() >= 1e-9 && t > T_MIN {
                t
            } else {
                f32::INFINITY
            }
        })
    }

    /// Per lane, the radiance the floor's mirror rays bring back (`reflect` at
    /// depth 1 with weight `r`): lanes whose rays meet none of the tile's mirror
    /// candidates see the background, found for all lanes at once; the others
    /// go through `reflect`.
    #[expect(clippy::too_many_arguments, reason = "the lanes' state, passed down")]
    #[inline(always)]
    fn mirrors(
        &self,
        floor: &Floor<'_>,
        (x0, y, on_floor): (u32, u32, [bool; LANES]),
        d: &V8,
        start: &V8,
        nv: &impl Fn(usize) -> Vec3,
        r: f32,
        tile: Option<(&Tiles, u32, u32)>,
    ) -> V8 {
        // dir - 2.0 * dir.dot(n) * n
        let dir = V8 {
            x: f8(|i| {
                let n = nv(i);
                d.x[i] - (2.0 * ((d.x[i] * n.x) + (d.y[i] * n.y) + (d.z[i] * n.z))) * n.x
            }),
            y: f8(|i| {
                let n = nv(i);
                d.y[i] - (2.0 * ((d.x[i] * n.x) + (d.y[i] * n.y) + (d.z[i] * n.z))) * n.y
            }),
            z: f8(|i| {
                let n = nv(i);
                d.z[i] - (2.0 * ((d.x[i] * n.x) + (d.y[i] * n.y) + (d.z[i] * n.z))) * n.z
            }),
        };
        // Lanes whose mirror ray meets none of the tile's mirror candidates see
        // the background (`closest_among` finds nothing): the planes' and the
        // others' box and hit tests over the lanes, as in `nearer_than`.
        let mut missed = [false; LANES];
        if let Some(list) = self.tiles.mirror_at(floor.object, x0, y) {
            let inv = V8 {
                x: f8(|i| 1.0 / dir.x[i]),
                y: f8(|i| 1.0 / dir.y[i]),
                z: f8(|i| 1.0 / dir.z[i]),
            };
            let far = [f32::INFINITY; LANES];
            let mut met = [false; LANES];
            for &k in list {
                if matches!(self.p.scene.objects[k].shape, Shape::Plane { .. }) {
                    let t = self.plane_hits(k, start, &dir);
                    for i in 0..LANES {
                        met[i] |= t[i] < f32::INFINITY;
                    }
                    continue;
                }
                let inside = box8(&self.p.boxes[k], start, &inv, &far);
                if inside.contains(&true) {
                    let hit = blocks8(self.p.geom(k), start, &dir, &far);
                    for i in 0..LANES {
                        met[i] |= inside[i] && hit[i];
                    }
                }
            }
            missed = met.map(|m| !m);
        }
        let bg = self.p.scene.background;
        let lanes: [Vec3; LANES] = lanes(|i| {
            if !on_floor[i] {
                return bg;
            }
            let mirror = Ray {
                origin: start.lane(i),
                dir: dir.lane(i),
            };
            if missed[i] {
                // `reflect` would find nothing and note the ray to infinity.
                self.note(i, &mirror, f32::INFINITY);
                return bg;
            }
            let mut motion = Motion::with(self.motion, self.scratch.take());
            let c = reflect(
                self.p,
                &mirror,
                floor.object,
                1,
                r,
                self.bound,
                &mut motion,
                tile,
            );
            if self.motion.is_some() {
                let mut m = self.marks.get();
                m[i] |= motion.mask;
                self.marks.set(m);
                let mut segs = self.segs.borrow_mut();
                segs.extend(motion.segs.drain(..).map(|s| (i as u8, s)));
            }
            motion.segs.clear();
            self.scratch.set(motion.segs);
            c
        });
        V8 {
            x: f8(|i| lanes[i].x),
            y: f8(|i| lanes[i].y),
            z: f8(|i| lanes[i].z),
        }
    }
}
