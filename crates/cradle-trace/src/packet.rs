//! Packets: eight adjacent pixels of a row traced together where the scene is
//! coherent, structure of arrays, one lane per pixel.
//!
//! A packet is taken when the only candidate whose screen rectangle reaches its
//! pixels is one plane (the open floor, most of the picture), and every lane's
//! ray meets that plane: then the closest hit of each lane is that plane's. Each lane then computes exactly what the scalar path computes
//! (`CameraRays::ray`, `hit_plane`, `shade`): the same IEEE operations in the same
//! order, with no fused multiply-add and no approximate reciprocal, so the bytes
//! equal the scalar render's. The lines carry the scalar expression they mirror.
//! Work that is not coherent (a shadow ray that may be blocked, a mirror ray with
//! objects to meet) goes lane by lane through the scalar queries themselves.
//!
//! The arithmetic is written over `[f32; 8]` arrays, which the compiler turns
//! into SIMD: SSE2 in the portable build, and AVX2 where the CPU has it, chosen at
//! run time (`floor_packet`).

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]
#![expect(
    clippy::needless_range_loop,
    reason = "a lane index reads several arrays at once"
)]

use super::camera::CameraRays;
use super::color::srgb8;
use super::geometry::{Ray, T_MIN};
use super::motion::Motion;
use super::prepared::Prepared;
use super::scene::{Light, Material, Shape};
use super::shade::{BAILOUT, SURFACE_OFFSET, blocked, floor_i64, reflect};
use super::tiles::Tiles;
use glam::Vec3;
use std::sync::atomic::{AtomicBool, Ordering};

/// Pixels per packet.
pub const LANES: usize = 8;

/// Set: packets take the portable build even where the CPU has AVX2.
static PORTABLE: AtomicBool = AtomicBool::new(false);

/// Makes packets use the portable (SSE2) build of the lane code even where the
/// CPU has AVX2, or lets them choose again. Both give the same bytes; tests use
/// this to check the build this machine would not otherwise run.
pub fn force_portable(on: bool) {
    PORTABLE.store(on, Ordering::Relaxed);
}

type F8 = [f32; LANES];

/// Eight vectors, one per lane.
#[derive(Clone, Copy)]
struct V8 {
    x: F8,
    y: F8,
    z: F8,
}

/// The lanes `f(0)..f(7)`. A plain loop, which inlines and vectorizes;
/// `std::array::from_fn` calls its closure through a wrapper that stays a call.
#[inline(always)]
fn f8(f: impl FnMut(usize) -> f32) -> F8 {
    lanes(f)
}

/// [`f8`] for any lane type.
#[inline(always)]
fn lanes<T: Copy + Default>(mut f: impl FnMut(usize) -> T) -> [T; LANES] {
    let mut out = [T::default(); LANES];
    for (i, o) in out.iter_mut().enumerate() {
        *o = f(i);
    }
    out
}

impl V8 {
    #[inline(always)]
    fn lane(&self, i: usize) -> Vec3 {
        Vec3::new(self.x[i], self.y[i], self.z[i])
    }

    /// `a.dot(b)`: `(a.x * b.x) + (a.y * b.y) + (a.z * b.z)`.
    #[inline(always)]
    fn dot(&self, b: Vec3) -> F8 {
        f8(|i| (self.x[i] * b.x) + (self.y[i] * b.y) + (self.z[i] * b.z))
    }
}

/// The floor plane a packet shades: its object, point, normal and material.
#[derive(Clone, Copy)]
pub(crate) struct Floor<'a> {
    object: usize,
    normal: Vec3,
    material: &'a Material,
    /// `(point - eye).dot(normal)`: the numerator of every primary ray's hit.
    num: f32,
}

impl<'a> Floor<'a> {
    /// Plane `object` (the only thing a packet's rays can hit).
    pub(crate) fn of(p: &'a Prepared<'_>, cam: &CameraRays, object: usize) -> Option<Self> {
        let o = &p.scene.objects[object];
        let Shape::Plane { point, normal } = o.shape else {
            return None;
        };
        Some(Self {
            object,
            normal,
            material: &o.material,
            // hit_plane: (point - ray.origin).dot(normal), the eye for every lane.
            num: (point - cam.origin).dot(normal),
        })
    }
}

/// What a packet needs besides its pixels.
pub(crate) struct Packet<'a, 'p> {
    pub(crate) p: &'a Prepared<'p>,
    pub(crate) cam: &'a CameraRays,
    pub(crate) tiles: &'a Tiles,
    pub(crate) bound: f32,
}

impl Packet<'_, '_> {
    /// Traces pixels `x0..x0 + 8` of row `y` at their centres into `out` (8 RGBA
    /// pixels) when `floor` is all their tile holds; false (nothing written) when a
    /// lane's ray misses it, for the scalar path to trace.
    pub(crate) fn floor(&self, floor: &Floor<'_>, x0: u32, y: u32, out: &mut [u8]) -> bool {
        #[cfg(target_arch = "x86_64")]
        if !PORTABLE.load(Ordering::Relaxed) && std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above.
            #[expect(unsafe_code, reason = "the one run-time dispatch to the AVX2 build")]
            return unsafe { self.floor_avx2(floor, x0, y, out) };
        }
        self.floor_lanes(floor, x0, y, out)
    }

    /// [`Self::floor_lanes`] compiled for AVX2 (8 lanes in one register); no FMA,
    /// which AVX2 does not imply.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn floor_avx2(&self, floor: &Floor<'_>, x0: u32, y: u32, out: &mut [u8]) -> bool {
        self.floor_lanes(floor, x0, y, out)
    }

    #[inline(always)]
    fn floor_lanes(&self, floor: &Floor<'_>, x0: u32, y: u32, out: &mut [u8]) -> bool {
        let c = self.cam;
        // CameraRays::ray(x + 0.5, y + 0.5).
        let sx = f8(|i| 2.0 * ((x0 + i as u32) as f32 + 0.5) / c.width - 1.0);
        let sy = 1.0 - 2.0 * (y as f32 + 0.5) / c.height;
        // (forward + right * sx + up * sy).normalize()
        let v = V8 {
            x: f8(|i| (c.forward.x + c.right.x * sx[i]) + c.up.x * sy),
            y: f8(|i| (c.forward.y + c.right.y * sx[i]) + c.up.y * sy),
            z: f8(|i| (c.forward.z + c.right.z * sx[i]) + c.up.z * sy),
        };
        let inv = f8(|i| 1.0 / ((v.x[i] * v.x[i]) + (v.y[i] * v.y[i]) + (v.z[i] * v.z[i])).sqrt());
        let d = V8 {
            x: f8(|i| v.x[i] * inv[i]),
            y: f8(|i| v.y[i] * inv[i]),
            z: f8(|i| v.z[i] * inv[i]),
        };
        // hit_plane: denom = dir.dot(normal); |denom| < 1e-9 misses;
        // t = num / denom; t > T_MIN hits.
        let denom = d.dot(floor.normal);
        let t = f8(|i| floor.num / denom[i]);
        // A miss (or a hit at infinity, which the closest-hit query does not take)
        // in any lane: the scalar path traces them all.
        let hits = |i: usize| denom[i].abs() >= 1e-9 && t[i] > T_MIN && t[i] < f32::INFINITY;
        if !(0..LANES).all(hits) {
            return false;
        }
        // closest_among: the normal faces the ray.
        let n = f8(|i| {
            if (floor.normal.x * d.x[i]) + (floor.normal.y * d.y[i]) + (floor.normal.z * d.z[i])
                > 0.0
            {
                -1.0
            } else {
                1.0
            }
        });
        let nv = |i: usize| {
            if n[i] < 0.0 {
                -floor.normal
            } else {
                floor.normal
            }
        };
        // point = ray.at(t): origin + dir * t
        let o = c.origin;
        let point = V8 {
            x: f8(|i| o.x + d.x[i] * t[i]),
            y: f8(|i| o.y + d.y[i] * t[i]),
            z: f8(|i| o.z + d.z[i] * t[i]),
        };
        let start = V8 {
            x: f8(|i| point.x[i] + nv(i).x * SURFACE_OFFSET),
            y: f8(|i| point.y[i] + nv(i).y * SURFACE_OFFSET),
            z: f8(|i| point.z[i] + nv(i).z * SURFACE_OFFSET),
        };
        let color = self.shade_lanes(floor, (x0, y), &d, &point, &start, &nv);
        for (i, px) in out.chunks_exact_mut(4).enumerate() {
            let c = color.lane(i);
            px.copy_from_slice(&[srgb8(c.x), srgb8(c.y), srgb8(c.z), 255]);
        }
        true
    }

    /// `shade` of floor hits at depth 0, lane by lane: `d` the rays' directions,
    /// `point` their hits, `start` the secondary rays' origins, `nv(i)` the normal.
    #[inline(always)]
    fn shade_lanes(
        &self,
        floor: &Floor<'_>,
        (x0, y): (u32, u32),
        d: &V8,
        point: &V8,
        start: &V8,
        nv: &impl Fn(usize) -> Vec3,
    ) -> V8 {
        let p = self.p;
        let m = floor.material;
        let tile = Some((self.tiles, x0, y));
        // base_color: a checker on the x-z grid, or plain.
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
        let mut color = V8 {
            x: [0.0; LANES],
            y: [0.0; LANES],
            z: [0.0; LANES],
        };
        for (li, light) in p.scene.lights.iter().enumerate() {
            let (to_light, dist, lc) = match *light {
                Light::Ambient { color: c } => {
                    // color += base * c
                    for i in 0..LANES {
                        color.x[i] += base[i].x * c.x;
                        color.y[i] += base[i].y * c.y;
                        color.z[i] += base[i].z * c.z;
                    }
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
                let n = nv(i);
                (n.x * to_light.x[i]) + (n.y * to_light.y[i]) + (n.z * to_light.z[i])
            });
            let blocked = self.shadows(floor, (x0, y, li), start, &to_light, &dist, &lambert, tile);
            for i in 0..LANES {
                if lambert[i] <= 0.0 || blocked[i] {
                    continue;
                }
                // color += base * light_color * lambert
                color.x[i] += (base[i].x * lc.x) * lambert[i];
                color.y[i] += (base[i].y * lc.y) * lambert[i];
                color.z[i] += (base[i].z * lc.z) * lambert[i];
                if let Some(exponent) = m.specular {
                    // mirrored = 2.0 * lambert * n - to_light; facing = mirrored.dot(-dir)
                    let (n, s) = (nv(i), 2.0 * lambert[i]);
                    let mx = s * n.x - to_light.x[i];
                    let my = s * n.y - to_light.y[i];
                    let mz = s * n.z - to_light.z[i];
                    let facing = (mx * -d.x[i]) + (my * -d.y[i]) + (mz * -d.z[i]);
                    if facing > 0.0 {
                        let k = facing.powf(exponent);
                        color.x[i] += lc.x * k;
                        color.y[i] += lc.y * k;
                        color.z[i] += lc.z * k;
                    }
                }
            }
        }
        let r = m.reflective;
        if r > 0.0 && 0 < p.scene.max_depth && r * self.bound >= BAILOUT {
            let refl = self.mirrors(floor, (x0, y), d, start, nv, r, tile);
            // color = color * (1.0 - r) + reflected * r
            for i in 0..LANES {
                color.x[i] = color.x[i] * (1.0 - r) + refl.x[i] * r;
                color.y[i] = color.y[i] * (1.0 - r) + refl.y[i] * r;
                color.z[i] = color.z[i] * (1.0 - r) + refl.z[i] * r;
            }
        }
        color
    }

    /// Per lane, whether the shadow ray from `start` towards light `li` is
    /// blocked (lanes facing away, `lambert <= 0`, are not traced). Where no
    /// caster can shadow the tile, only the planes are tested, all lanes at once.
    #[expect(clippy::too_many_arguments, reason = "the lanes' state, passed down")]
    #[inline(always)]
    fn shadows(
        &self,
        floor: &Floor<'_>,
        (x0, y, li): (u32, u32, usize),
        start: &V8,
        to_light: &V8,
        dist: &F8,
        lambert: &F8,
        tile: Option<(&Tiles, u32, u32)>,
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
        let mut motion = Motion::new(None);
        lanes(|i| {
            lambert[i] > 0.0 && {
                let shadow = Ray {
                    origin: start.lane(i),
                    dir: to_light.lane(i),
                };
                blocked(
                    self.p,
                    &shadow,
                    dist[i],
                    (floor.object, li),
                    tile,
                    &mut motion,
                )
            }
        })
    }

    /// Per lane, where the ray from `origin` along `dir` meets plane object `k`
    /// (`hit_plane`), or infinity for a miss.
    #[inline(always)]
    fn plane_hits(&self, k: usize, origin: &V8, dir: &V8) -> F8 {
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
    /// depth 1 with weight `r`): when the tile's mirror candidates are planes
    /// only, lanes whose rays miss them see the background, all at once.
    #[expect(clippy::too_many_arguments, reason = "the lanes' state, passed down")]
    #[inline(always)]
    fn mirrors(
        &self,
        floor: &Floor<'_>,
        (x0, y): (u32, u32),
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
        let list = self.tiles.mirror_at(floor.object, x0, y).unwrap_or(&[]);
        let planes_only = !list.is_empty()
            && list
                .iter()
                .all(|&k| matches!(self.p.scene.objects[k].shape, Shape::Plane { .. }));
        let mut missed = [false; LANES];
        if planes_only {
            let mut nearest = [f32::INFINITY; LANES];
            for &k in list {
                let t = self.plane_hits(k, start, &dir);
                for i in 0..LANES {
                    nearest[i] = nearest[i].min(t[i]);
                }
            }
            missed = f8(|i| nearest[i]).map(|t| t == f32::INFINITY);
        }
        let bg = self.p.scene.background;
        let mut motion = Motion::new(None);
        let lanes: [Vec3; LANES] = lanes(|i| {
            if missed[i] {
                return bg;
            }
            let mirror = Ray {
                origin: start.lane(i),
                dir: dir.lane(i),
            };
            reflect(
                self.p,
                &mirror,
                floor.object,
                1,
                r,
                self.bound,
                &mut motion,
                tile,
            )
        });
        V8 {
            x: f8(|i| lanes[i].x),
            y: f8(|i| lanes[i].y),
            z: f8(|i| lanes[i].z),
        }
    }
}
