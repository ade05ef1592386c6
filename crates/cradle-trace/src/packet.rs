//! Packets: eight adjacent pixels of a row traced together where the scene is
//! coherent, structure of arrays, one lane per pixel.
//!
//! A packet is taken when the only plane among the candidates whose screen
//! rectangles reach its pixels is the floor (most of the picture), and every
//! lane's ray meets it; lanes that meet another candidate first (the cradle) are
//! traced on from that hit over the lanes.
//! Each lane computes exactly what the scalar path computes (`CameraRays::ray`,
//! `hit_plane`, `shade`): the same IEEE operations in the same order, with no
//! fused multiply-add and no approximate reciprocal, so the bytes equal the
//! scalar render's. The lines carry the scalar expression they mirror.
//! What lies past the floor's own shading (the cradle, its mirror image, the
//! reflections in it) is traced on over the lanes, bounce by bounce (`bounce`).
//!
//! The kernel is written once over a lane build `S: Simd` (`crate::simd`): one
//! AVX instruction per operation where the CPU has AVX2 (chosen at run time, in
//! `Packet::floor`), plain loops over arrays elsewhere. Rays and hits are here,
//! the shading in `lanes`, the bounces past it in `bounce` (their nearest hits
//! in `nearest`), the objects met on the way in `occlusion` and `objects`, the
//! lane vectors in `vec`. A plane's own shadow and mirror rays never test it
//! (`Prepared::closest_from`), here as in the scalar path.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::camera::CameraRays;
use super::geometry::SURFACE_OFFSET;
use super::geometry::T_MIN;
use super::motion::{Cells, Motion, MotionGrid, Seg};
use super::prepared::Prepared;
use super::scene::{Material, Shape};
use super::simd::{Build, Kernel, Simd};
use super::tiles::{Reaching, Tiles};
use glam::Vec3;
use std::cell::{Cell, RefCell};

/// Pixels per packet.
pub const LANES: usize = 8;

mod bounce;
mod hits;
#[cfg(test)]
mod lane_tests;
mod lanes;
mod lookup;
mod nearest;
mod notes;
mod objects;
mod occlusion;
mod rays;
mod samples;
pub(crate) mod spare;
mod vec;

use vec::{L3, Surface, load3, splat3, store3};

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

/// The lanes of `among` (bits) whose `keys` equal `key`. (A plain loop, no
/// closure: it inlines into the AVX2 build.)
#[inline(always)]
fn lanes_with<T: PartialEq>(keys: &[T; LANES], key: &T, among: u8) -> u8 {
    let mut bits = 0u8;
    for (i, k) in keys.iter().enumerate() {
        if k == key {
            bits |= 1 << i;
        }
    }
    bits & among
}

impl V8 {
    const ZERO: V8 = V8 {
        x: [0.0; LANES],
        y: [0.0; LANES],
        z: [0.0; LANES],
    };

    #[inline(always)]
    fn lane(&self, i: usize) -> Vec3 {
        Vec3::new(self.x[i], self.y[i], self.z[i])
    }

    /// Sets lane `i` to `v`.
    fn set(&mut self, i: usize, v: Vec3) {
        (self.x[i], self.y[i], self.z[i]) = (v.x, v.y, v.z);
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
    /// The segments of each lane's rays inside the motion box, in the order
    /// traced (with `motion`).
    pub(crate) segs: RefCell<[Vec<Seg>; LANES]>,
    /// The linear colours of the last packet's lanes (those it wrote), as
    /// red, green and blue lanes: see [`Self::color`].
    pub(crate) colors: Cell<[F8; 3]>,
}

impl Drop for Packet<'_, '_> {
    /// Gives the lanes' segment buffers back to the thread's spares.
    fn drop(&mut self) {
        spare::give(std::mem::take(self.segs.get_mut()));
    }
}

impl Packet<'_, '_> {
    /// Traces pixels `x..x + 8` of row `y` into `span` (8 RGBA pixels) where
    /// the floor is the one plane their tile offers and the nearest hit
    /// ([`Self::floor`]): the lanes written (their cells: [`Self::marks`]).
    #[inline(always)]
    pub(crate) fn run(&self, x: u32, y: u32, span: &mut [u8]) -> u8 {
        let mut others = Reaching::default();
        match self
            .tiles
            .plane_among(self.p, (x, y, LANES as u32), &mut others)
        {
            Some(plane) => Floor::of(self.p, self.cam, plane)
                .map_or(0, |f| self.floor(&f, others.as_slice(), x, y, span)),
            None => 0,
        }
    }

    /// Forgets the last packet's cells and segments (in a tracked frame).
    pub(crate) fn fresh(&self) {
        if self.motion.is_some() {
            self.marks.set([0; LANES]);
            self.segs.borrow_mut().iter_mut().for_each(Vec::clear);
        }
    }

    /// The cells each lane's rays passed through in the last packet (in a
    /// tracked frame).
    pub(crate) fn marks(&self) -> [Cells; LANES] {
        self.marks.get()
    }

    /// What `f` returns, given a `Motion` for lane `i` (lent the lane's
    /// segments, to append to) whose cells then go to the lane's in a tracked
    /// frame: the scalar path's tracing of one lane.
    pub(crate) fn in_lane(&self, i: usize, f: impl FnOnce(&mut Motion) -> Vec3) -> Vec3 {
        let lent = std::mem::take(&mut self.segs.borrow_mut()[i]);
        let mut motion = Motion::with(self.motion, lent);
        let c = f(&mut motion);
        if self.motion.is_some() {
            let m = &self.marks.as_array_of_cells()[i];
            m.set(m.get() | motion.mask);
        }
        self.segs.borrow_mut()[i] = motion.segs;
        c
    }

    /// Lane `i`'s linear colour in the last packet.
    pub(crate) fn color(&self, i: usize) -> Vec3 {
        let [r, g, b] = self.colors.get();
        Vec3::new(r[i], g[i], b[i])
    }

    /// Appends the segments lane `i` noted in the last packet to `out`.
    pub(crate) fn lane_segs(&self, i: usize, out: &mut Vec<Seg>) {
        out.extend_from_slice(&self.segs.borrow()[i]);
    }

    /// Traces pixels `x0..x0 + 8` of row `y` at their centres into `out` (8 RGBA
    /// pixels) where the nearest hit is `floor` (`others`: the other objects that
    /// can be met there, and are traced on from there in the lanes they stop):
    /// a bit per lane written, all or none. When any lane's ray misses the
    /// floor, all are left for the scalar path.
    pub(crate) fn floor(
        &self,
        floor: &Floor<'_>,
        others: &[usize],
        x0: u32,
        y: u32,
        out: &mut [u8],
    ) -> u8 {
        self.fresh();
        Build::detect().run(FloorKernel {
            pk: self,
            floor,
            others,
            at: (x0, y),
            out,
        })
    }

    /// The packet's lanes in lane build `S`: the lanes written (a bit each) and
    /// their linear colours, also kept in `colors`.
    #[inline(always)]
    fn floor_lanes<S: Simd>(
        &self,
        s: S,
        floor: &Floor<'_>,
        others: &[usize],
        x0: u32,
        y: u32,
    ) -> (u8, V8) {
        let c = self.cam;
        let k = |v: f32| s.splat(v);
        // CameraRays::ray(x + 0.5, y + 0.5).
        let xs = s.load(&f8(|i| (x0 + i as u32) as f32));
        let sx = k(2.0) * (xs + k(0.5)) / k(c.width) - k(1.0);
        let sy = 1.0 - 2.0 * (y as f32 + 0.5) / c.height;
        // (forward + right * sx + up * sy).normalize()
        let v = L3 {
            x: (k(c.forward.x) + k(c.right.x) * sx) + k(c.up.x * sy),
            y: (k(c.forward.y) + k(c.right.y) * sx) + k(c.up.y * sy),
            z: (k(c.forward.z) + k(c.right.z) * sx) + k(c.up.z * sy),
        };
        let inv = k(1.0) / S::sqrt(v.dot(&v));
        let d = v.scale(inv);
        // hit_plane: denom = dir.dot(normal); |denom| < 1e-9 misses;
        // t = num / denom; t > T_MIN hits.
        let denom = d.dot(&splat3(s, floor.normal));
        let t = k(floor.num) / denom;
        // A miss (or a hit at infinity, which the closest-hit query does not take)
        // in any lane: the scalar path traces them all.
        let hits = S::le(k(1e-9), S::abs(denom)) & S::lt(k(T_MIN), t) & S::lt(t, k(f32::INFINITY));
        if S::bits(hits) != 0xFF {
            return (0, V8::ZERO);
        }
        // closest_among, after the plane: each other candidate through its box
        // with the nearest hit so far as the limit. Lanes that meet one first
        // are traced on from there (`bounce`).
        let (front, found) = if others.is_empty() {
            let none = nearest::Found {
                missed: 0,
                which: k(0.0),
                at: None,
            };
            (0, none)
        } else {
            self.nearest_of(s, others, &d, t)
        };
        let on_floor = !front;
        // Camera rays: free (`Record::segment`'s `free`).
        self.note_lanes(s, (on_floor, 0xFF), (&splat3(s, c.origin), &d), t);
        // closest_among: the normal faces the ray (`denom` is normal.dot(dir)).
        let back = S::lt(k(0.0), denom);
        let nn = L3 {
            x: S::select(back, k(-floor.normal.x), k(floor.normal.x)),
            y: S::select(back, k(-floor.normal.y), k(floor.normal.y)),
            z: S::select(back, k(-floor.normal.z), k(floor.normal.z)),
        };
        // point = ray.at(t): origin + dir * t; start = point + n * SURFACE_OFFSET
        let point = splat3(s, c.origin).add(&d.scale(t));
        let start = point.add(&nn.scale(k(SURFACE_OFFSET)));
        let hit = Surface {
            d,
            point,
            start,
            nn,
        };
        let mut color = if on_floor == 0 {
            splat3(s, Vec3::ZERO)
        } else {
            self.shade_lanes(s, floor, (x0, y), on_floor, &hit)
        };
        if front != 0 {
            let ray = rays::Bounce {
                origin: splat3(s, c.origin),
                d,
                depth: 0,
                weight: k(1.0),
                free: 0,
                from: k(-1.0),
            };
            let cradle = self.bounce(s, &ray, front, Some(found));
            color = vec::select3::<S>(s.mask(front), &cradle, &color);
        }
        let color = store3::<S>(&color);
        self.colors.set([color.x, color.y, color.z]);
        (0xFF, color)
    }
}

/// Writes the pixels `px` of the lanes in `done` to `out`, 8 RGBA pixels.
#[inline(always)]
fn write(out: &mut [u8], done: u8, px: [u32; LANES]) {
    if done == 0xFF {
        for (o, p) in out.chunks_exact_mut(4).zip(px) {
            o.copy_from_slice(&p.to_le_bytes());
        }
        return;
    }
    for (i, (o, p)) in out.chunks_exact_mut(4).zip(px).enumerate() {
        if done >> i & 1 != 0 {
            o.copy_from_slice(&p.to_le_bytes());
        }
    }
}

/// [`Packet::floor`]'s lanes as a lane kernel: trace them, and write the
/// lanes done as RGBA into `out`.
struct FloorKernel<'k, 'p, 'a> {
    pk: &'k Packet<'p, 'a>,
    floor: &'k Floor<'k>,
    others: &'k [usize],
    at: (u32, u32),
    out: &'k mut [u8],
}

#[expect(
    clippy::inline_always,
    reason = "a kernel inlines into its build's entry point, which compiles it for AVX2 in the AVX2 build"
)]
impl Kernel for FloorKernel<'_, '_, '_> {
    type Output = u8;
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> u8 {
        let (done, c) = self
            .pk
            .floor_lanes(s, self.floor, self.others, self.at.0, self.at.1);
        if done != 0 {
            write(self.out, done, s.rgba8(&c.x, &c.y, &c.z));
        }
        done
    }
}
