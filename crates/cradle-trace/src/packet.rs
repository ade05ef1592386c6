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
//! run time (`floor_packet`). The shading of the lanes is in `lanes`.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::camera::CameraRays;
use super::color::srgb8_lanes;
use super::geometry::{Ray, T_MIN};
use super::motion::{Cells, MotionGrid, Seg};
use super::prepared::Prepared;
use super::scene::{Material, Shape};
use super::shade::SURFACE_OFFSET;
use super::tiles::Tiles;
use glam::Vec3;
use std::cell::{Cell, RefCell};

/// Pixels per packet.
pub const LANES: usize = 8;

#[cfg(target_arch = "x86_64")]
mod avx;
#[cfg(test)]
mod lane_tests;
mod lanes;
mod occlusion;

pub use super::simd::force_portable;

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
    /// The motion grid of a tracked frame: each lane notes the cells its rays
    /// pass through, as the scalar path does.
    pub(crate) motion: Option<MotionGrid>,
    /// The cells each lane's rays passed through (with `motion`).
    pub(crate) marks: Cell<[Cells; LANES]>,
    /// The segments of the lanes' rays inside the motion box, with their lane, in
    /// the order traced (with `motion`).
    pub(crate) segs: RefCell<Vec<(u8, Seg)>>,
    /// A buffer lent to the scalar path's `Motion` for a lane.
    pub(crate) scratch: Cell<Vec<Seg>>,
    /// The linear colours of the last packet's lanes (those it wrote), as
    /// red, green and blue lanes: see [`Self::color`].
    pub(crate) colors: Cell<[F8; 3]>,
}

impl Packet<'_, '_> {
    /// Traces pixels `x..x + 8` of row `y` into `span` (8 RGBA pixels) where
    /// the floor is the one plane their tile offers and the nearest hit
    /// ([`Self::floor`]): the lanes written, and in a tracked frame their cells.
    #[inline]
    pub(crate) fn run(&self, x: u32, y: u32, span: &mut [u8]) -> (u8, [Cells; LANES]) {
        let done = match self.tiles.plane_among(self.p, x, y, LANES as u32) {
            Some((plane, others)) => Floor::of(self.p, self.cam, plane)
                .map_or(0, |f| self.floor(&f, others.as_slice(), x, y, span)),
            None => 0,
        };
        (done, self.marks.get())
    }

    /// Notes the cells the segment of `ray` up to `t` passes through, and its part
    /// in the motion box, for lane `i` (what `Motion::segment` notes for a pixel).
    #[inline]
    pub(crate) fn note(&self, i: usize, ray: &Ray, t: f32) {
        if let Some(g) = &self.motion
            && let Some(s) = g.clip(ray, t)
        {
            let mut m = self.marks.get();
            m[i] |= g.cells(s.a.min(s.b), s.a.max(s.b));
            self.marks.set(m);
            self.segs.borrow_mut().push((i as u8, s));
        }
    }

    /// Lane `i`'s linear colour in the last packet.
    pub(crate) fn color(&self, i: usize) -> Vec3 {
        let [r, g, b] = self.colors.get();
        Vec3::new(r[i], g[i], b[i])
    }

    /// Appends the segments lane `i` noted in the last packet to `out`.
    pub(crate) fn lane_segs(&self, i: usize, out: &mut Vec<Seg>) {
        let segs = self.segs.borrow();
        out.extend(
            segs.iter()
                .filter(|(l, _)| usize::from(*l) == i)
                .map(|(_, s)| *s),
        );
    }

    /// Traces pixels `x0..x0 + 8` of row `y` at their centres into `out` (8 RGBA
    /// pixels) where the nearest hit is `floor` (`others`: the other objects that
    /// can be met there): a bit per lane written. The other lanes (a ray that
    /// misses the floor, or meets another object first; all of them when any
    /// lane misses the floor) are left for the scalar path.
    pub(crate) fn floor(
        &self,
        floor: &Floor<'_>,
        others: &[usize],
        x0: u32,
        y: u32,
        out: &mut [u8],
    ) -> u8 {
        if self.motion.is_some() {
            self.marks.set([0; LANES]);
            self.segs.borrow_mut().clear();
        }
        #[cfg(target_arch = "x86_64")]
        if super::simd::avx2() {
            // SAFETY: the CPU has AVX2, checked just above.
            #[expect(unsafe_code, reason = "the one run-time dispatch to the AVX2 build")]
            return unsafe { self.floor_avx2(floor, others, x0, y, out) };
        }
        self.floor_lanes::<false>(floor, others, x0, y, out)
    }

    /// [`Self::floor_lanes`] compiled for AVX2 (8 lanes in one register); no FMA,
    /// which AVX2 does not imply.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn floor_avx2(
        &self,
        floor: &Floor<'_>,
        others: &[usize],
        x0: u32,
        y: u32,
        out: &mut [u8],
    ) -> u8 {
        self.floor_lanes::<true>(floor, others, x0, y, out)
    }

    /// The packet's lanes; `AVX2`: compiled into the AVX2 build, which may use
    /// its instructions directly (the sRGB gathers).
    #[inline(always)]
    fn floor_lanes<const AVX2: bool>(
        &self,
        floor: &Floor<'_>,
        others: &[usize],
        x0: u32,
        y: u32,
        out: &mut [u8],
    ) -> u8 {
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
            return 0;
        }
        // closest_among, after the plane: each other candidate through its box
        // with the plane's t as the limit. Lanes that meet one first are the
        // scalar path's.
        let front = if others.is_empty() {
            [false; LANES]
        } else {
            self.nearer_than(others, &d, &t)
        };
        if !front.contains(&false) {
            return 0;
        }
        let on_floor: [bool; LANES] = std::array::from_fn(|i| !front[i]);
        if self.motion.is_some() {
            for (i, _) in on_floor.iter().enumerate().filter(|(_, f)| **f) {
                let ray = Ray {
                    origin: c.origin,
                    dir: d.lane(i),
                };
                self.note(i, &ray, t[i]);
            }
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
        let color = self.shade_lanes(floor, (x0, y), on_floor, (&d, &point, &start), &nv);
        let srgb = |c: F8| {
            #[cfg(target_arch = "x86_64")]
            if AVX2 {
                // SAFETY: `AVX2` is set only in the AVX2 build, which runs only
                // where the CPU has it.
                #[expect(unsafe_code, reason = "the AVX2 build's sRGB gathers")]
                return unsafe { super::color::srgb8_avx2(c) };
            }
            srgb8_lanes(c)
        };
        self.colors.set([color.x, color.y, color.z]);
        let (r, g, b) = (srgb(color.x), srgb(color.y), srgb(color.z));
        let mut done = 0u8;
        for (i, px) in out.chunks_exact_mut(4).enumerate() {
            if on_floor[i] {
                px.copy_from_slice(&[r[i], g[i], b[i], 255]);
                done |= 1 << i;
            }
        }
        done
    }
}
