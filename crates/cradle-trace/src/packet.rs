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
//! `Packet::floor`), plain loops over arrays elsewhere. Its types, bottom up:
//! the lane vectors (`vec`), hit tests (`hits`, `lookup`) and rays (`rays`);
//! [`Scan`], the scene's nearest-hit and shadow queries over the lanes;
//! [`LaneNotes`], what the lanes' rays pass through in a tracked frame;
//! [`Lights`], a surface's lights and shadow rays; [`Bounces`], the rays past
//! a first hit, level by level; and the packet itself, the eye's rays to the
//! floor, its shading and mirror rays, and anti-aliasing's extra samples. A
//! plane's own shadow and mirror rays never test it (`Prepared::closest_from`),
//! here as in the scalar path.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::camera::CameraRays;
use super::geometry::SURFACE_OFFSET;
use super::geometry::T_MIN;
use super::material::BAILOUT;
use super::prepared::Prepared;
use super::simd::{Build, Kernel, Portable, Simd};
use super::tiles::{Reaching, Tiles};
use glam::Vec3;
use std::cell::Cell;

/// Pixels per packet.
pub const LANES: usize = 8;

mod bounce;
mod hits;
#[cfg(test)]
mod lane_tests;
mod lights;
mod lookup;
mod nearest;
mod notes;
mod rays;
mod scan;
mod spare;
mod vec;

use bounce::{Bounces, bounce_copy};
use lights::Lights;
pub(crate) use notes::LaneNotes;
use rays::{Bounce, Bounce8, Floor, Met};
use scan::Scan;
use vec::{F8, L3, Surface, V8, f8, select3, splat3, store3};

pub use super::simd::force_portable;

/// A packet tracer: the frame's prepared scene, camera, tiles and radiance
/// bound, the notes its lanes leave in a tracked frame, and the colours of the
/// last packet.
pub(crate) struct Packet<'a, 'p> {
    p: &'a Prepared<'p>,
    cam: &'a CameraRays,
    tiles: &'a Tiles,
    bound: f32,
    /// What each lane's rays passed through (in a tracked frame).
    pub(crate) notes: LaneNotes,
    /// The linear colours of the last packet's lanes (those it wrote), as
    /// red, green and blue lanes: see [`Self::color`].
    colors: Cell<[F8; 3]>,
}

impl<'a, 'p> Packet<'a, 'p> {
    /// A packet tracer of the frame prepared as `p`, seen through `cam`, its
    /// candidates in `tiles`, with radiance bound `bound`, noting its lanes'
    /// motion in `notes`.
    pub(crate) fn new(
        (p, cam, tiles): (&'a Prepared<'p>, &'a CameraRays, &'a Tiles),
        bound: f32,
        notes: LaneNotes,
    ) -> Self {
        Self {
            p,
            cam,
            tiles,
            bound,
            notes,
            colors: Cell::new([[0.0; LANES]; 3]),
        }
    }

    /// Traces pixels `x..x + 8` of row `y` into `span` (8 RGBA pixels) where
    /// the floor is the one plane their tile offers and the nearest hit
    /// ([`Self::floor`]): the lanes written (their cells: `notes`).
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

    /// Lane `i`'s linear colour in the last packet.
    pub(crate) fn color(&self, i: usize) -> Vec3 {
        let [r, g, b] = self.colors.get();
        Vec3::new(r[i], g[i], b[i])
    }

    /// The radiance of the camera rays through the picture points `at` (at
    /// most [`LANES`]; lane `i` is `at[i]`), as `CameraRays::ray` makes them,
    /// each traced by the bounces from the eye as the scalar `trace_primary`
    /// traces it: anti-aliasing's extra samples (the tile's lists only skip
    /// what cannot be met). In a tracked frame each lane's cells and segments
    /// are noted, those of earlier calls dropped.
    pub(crate) fn camera_samples(&self, at: &[(f32, f32)]) -> [Vec3; LANES] {
        assert!(at.len() <= LANES, "at most {LANES} samples at a time");
        self.notes.fresh();
        let mut first = Bounce8 {
            origin: V8::ZERO,
            d: V8::ZERO,
            depth: 0,
            weight: [1.0; LANES],
            free: 0,
            from: [-1.0; LANES],
        };
        let mut live = 0u8;
        for (i, &(x, y)) in at.iter().enumerate() {
            let ray = self.cam.ray(x, y);
            first.origin.set(i, ray.origin);
            first.d.set(i, ray.dir);
            live |= 1 << i;
        }
        let c = match (Build::detect(), self.notes.tracked()) {
            (Build::Portable, false) => {
                bounce_copy(Portable, self.bounces::<false>(), &first, live, None)
            }
            (Build::Portable, true) => {
                bounce_copy(Portable, self.bounces::<true>(), &first, live, None)
            }
            #[cfg(target_arch = "x86_64")]
            (Build::Avx2(s), false) => bounce_copy(s, self.bounces::<false>(), &first, live, None),
            #[cfg(target_arch = "x86_64")]
            (Build::Avx2(s), true) => bounce_copy(s, self.bounces::<true>(), &first, live, None),
        };
        std::array::from_fn(|i| Vec3::new(c.x[i], c.y[i], c.z[i]))
    }

    /// The scene's queries over the lanes, noting what a tracked frame (`T`)
    /// needs.
    #[inline(always)]
    fn scan<const T: bool>(&self) -> Scan<'_, 'p, T> {
        Scan {
            p: self.p,
            first: self.notes.first_blockers(),
        }
    }

    /// The lights of what the lanes meet.
    #[inline(always)]
    fn lights<const T: bool>(&self) -> Lights<'_, 'p, T> {
        Lights {
            scan: self.scan(),
            notes: &self.notes,
        }
    }

    /// The bounces of the lanes' rays.
    #[inline(always)]
    fn bounces<const T: bool>(&self) -> Bounces<'_, 'p, T> {
        Bounces {
            lights: self.lights(),
            bound: self.bound,
        }
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
        self.notes.fresh();
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
    fn floor_lanes<S: Simd, const T: bool>(
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
            self.scan::<T>().nearest_of(s, others, (c.origin, &d), t)
        };
        let on_floor = !front;
        // Camera rays: free (`Record::segment`'s `free`).
        self.notes
            .note::<T, S>(s, (on_floor, 0xFF), (&splat3(s, c.origin), &d), t);
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
            self.shade_lanes::<S, T>(s, floor, (x0, y), on_floor, &hit)
        };
        if front != 0 {
            let ray = Bounce {
                origin: splat3(s, c.origin),
                d,
                depth: 0,
                weight: k(1.0),
                free: 0,
                from: k(-1.0),
            };
            let cradle = self.bounces::<T>().trace(s, &ray, front, Some(found));
            color = select3::<S>(s.mask(front), &cradle, &color);
        }
        let color = store3::<S>(&color);
        self.colors.set([color.x, color.y, color.z]);
        (0xFF, color)
    }

    /// `shade` at depth 0 of the floor lanes `on` (a bit each) at `hit`: what
    /// [`Lights::local`] gives, blended with what the mirror rays bring.
    #[inline(always)]
    fn shade_lanes<S: Simd, const T: bool>(
        &self,
        s: S,
        floor: &Floor<'_>,
        (x0, y): (u32, u32),
        on: u8,
        hit: &Surface<S::F>,
    ) -> L3<S::F> {
        // Camera rays met the floor: their shadow rays are free.
        let mut color = self
            .lights::<T>()
            .local(s, Met::Floor(floor), (on, 0xFF), hit);
        let r = floor.material.reflective;
        // weight * r * bound, at weight 1.
        if r > 0.0 && 0 < self.p.scene.max_depth && r * self.bound >= BAILOUT {
            let refl = self.mirrors::<S, T>(s, floor, (x0, y, on), hit, r);
            // color = color * (1.0 - r) + reflected * r
            let k = |v: f32| s.splat(v);
            color = color.scale(k(1.0 - r)).add(&refl.scale(k(r)));
        }
        color
    }

    /// Per lane, the radiance the floor's mirror rays bring back (`reflect` at
    /// depth 1 with weight `r`): the nearest hit among the tile's mirror
    /// candidates, found over the lanes, then traced on over the lanes
    /// ([`Bounces::trace`]). A packet whose lanes all meet nothing takes the
    /// background at once.
    #[inline(always)]
    fn mirrors<S: Simd, const T: bool>(
        &self,
        s: S,
        floor: &Floor<'_>,
        (x0, y, on_floor): (u32, u32, u8),
        Surface { d, start, nn, .. }: &Surface<S::F>,
        r: f32,
    ) -> L3<S::F> {
        // dir - 2.0 * dir.dot(n) * n
        let dir = d.sub(&nn.scale(s.splat(2.0) * d.dot(nn)));
        // The nearest of the tile's mirror candidates per lane (not the floor
        // itself, `Prepared::closest_among`); lanes that meet none see the
        // background.
        let mut missed = 0u8;
        let mut found = None;
        if let Some(list) = self.tiles.mirror_at(floor.object, x0, y) {
            let f = self
                .scan::<T>()
                .nearest_in(s, (list, floor.object), (start, &dir), on_floor);
            missed = f.missed;
            found = Some(f);
        }
        if on_floor & !missed == 0 && !T {
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
        self.bounces::<T>().trace(s, &mirror, on_floor, found)
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
struct FloorKernel<'k, 'a, 'p> {
    pk: &'k Packet<'a, 'p>,
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
        let (pk, (x0, y)) = (self.pk, self.at);
        let (done, c) = if pk.notes.tracked() {
            pk.floor_lanes::<S, true>(s, self.floor, self.others, x0, y)
        } else {
            pk.floor_lanes::<S, false>(s, self.floor, self.others, x0, y)
        };
        if done != 0 {
            write(self.out, done, s.rgba8(&c.x, &c.y, &c.z));
        }
        done
    }
}
