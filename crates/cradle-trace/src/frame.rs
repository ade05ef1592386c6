//! What a frame prepares and the per-pixel and per-row tracing the frame
//! drivers share: the scene made ready ([`Prepared`]), the camera's rays, the
//! tiles' lists, the sample offsets and the edge threshold ([`Frame`]); a pixel
//! by the scalar path, a row in packets where the tile allows, with its motion
//! record in a tracked frame. Above the tracer's kernels (`shade`, `packet`),
//! below the drivers (`render`, `adaptive`, `incremental`).

use super::camera::CameraRays;
use super::casters::Casters;
use super::color::srgb8;
use super::geometry::Aabb;
use super::material::radiance_bound;
use super::motion::{Cells, Motion, MotionGrid, NoRecord, Record, RowMotion, Seg};
use super::packet::{LANES, LaneNotes, Packet};
use super::prepared::{Kept, PerPlane, Prepared};
use super::reference::{self, Plain};
use super::sampling::sample_offsets;
use super::scene::Scene;
use super::shade::{trace, trace_primary};
use super::tiles::Tiles;
use glam::Vec3;

/// Which work-skipping the renderer may use. Each leaves the picture byte for byte
/// as the full render makes it (tested); turning them off gives that reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[expect(
    clippy::struct_excessive_bools,
    reason = "four independent switches, each one skip the tests and `bench render --without` turn on and off"
)]
pub struct RenderOptions {
    /// Primary rays test only the objects whose screen bounds cover their tile.
    pub tile_culling: bool,
    /// Shadow rays from a plane test only the objects whose shadow can fall there.
    pub shadow_culling: bool,
    /// Secondary rays walk a bounding volume hierarchy instead of every box.
    pub bvh: bool,
    /// Eight pixels' centre samples at a time, in SIMD lanes (needs
    /// `tile_culling`: a packet takes its tile's lists).
    pub packets: bool,
}

impl RenderOptions {
    /// Every skip on: what the app, `render` and `bench` use.
    pub const FAST: Self = Self {
        tile_culling: true,
        shadow_culling: true,
        bvh: true,
        packets: true,
    };
    /// Nothing skipped: the reference the skips are tested against.
    pub const FULL: Self = Self {
        tile_culling: false,
        shadow_culling: false,
        bvh: false,
        packets: false,
    };
}

/// Everything one row needs, shared by the serial and parallel paths.
pub(crate) struct Frame<'a> {
    prepared: Prepared<'a>,
    tiles: Option<Tiles>,
    camera: CameraRays,
    offsets: Vec<(f32, f32)>,
    bound: f32,
    width: u32,
    height: u32,
    pub(crate) motion: Option<MotionGrid>,
    /// Centre samples go in packets where the tile allows.
    packets: bool,
    /// Adaptive anti-aliasing: the byte difference above which a pixel is an edge.
    edge: Option<f32>,
}

impl<'a> Frame<'a> {
    /// `track`: note which pixels' rays enter the motion box (incremental frames only).
    pub(crate) fn new(scene: &'a Scene, options: RenderOptions, track: bool) -> Self {
        Self::with_kept(scene, options, track, None)
    }

    /// [`Self::new`], keeping what holds of the shadow casters of the frame
    /// before ([`Kept`]).
    pub(crate) fn with_kept(
        scene: &'a Scene,
        options: RenderOptions,
        track: bool,
        kept: Option<Kept>,
    ) -> Self {
        // The hierarchy first: the shadow casters find theirs through it.
        let prepared = Prepared::new(scene)
            .with_bvh(options.bvh)
            .with_shadow_culling_kept(options.shadow_culling, kept);
        let bound = radiance_bound(scene);
        let camera = CameraRays::new(&scene.camera, scene.size.0, scene.size.1);
        Self {
            tiles: options
                .tile_culling
                .then(|| Tiles::new(&prepared, &camera, scene.size.0, scene.size.1)),
            camera,
            offsets: sample_offsets(scene.samples),
            prepared,
            bound,
            width: scene.size.0,
            height: scene.size.1,
            edge: scene
                .adaptive
                .filter(|_| scene.samples > 1)
                .map(|t| t * 255.0),
            packets: options.packets,
            motion: scene
                .motion_bounds
                .filter(|_| track)
                .map(|(min, max)| MotionGrid::new(Aabb { min, max })),
        }
    }

    /// The linear colour of pixel `(x, y)` from samples at `offsets` (after
    /// `first`, the colour of a sample traced before, where given: the sum then
    /// makes the same additions in the same order as with that sample first in
    /// `offsets`), and the motion cells its rays passed through; their segments in
    /// the motion box are appended to `segs`.
    fn pixel(
        &self,
        (x, y): (u32, u32),
        first: Option<Vec3>,
        offsets: &[(f32, f32)],
        segs: &mut Vec<Seg>,
    ) -> (Vec3, Cells) {
        if self.motion.is_none() {
            return (self.samples((x, y), first, offsets, &mut NoRecord), 0);
        }
        let mut motion = Motion::with(self.motion, std::mem::take(segs));
        let c = self.samples((x, y), first, offsets, &mut motion);
        *segs = motion.segs;
        (c, motion.mask)
    }

    /// [`Self::pixel`]'s colour, its rays' segments noted in `record`: by the
    /// tiles' fast path, or without tiles by the scalar path (recording) or the
    /// reference (not).
    fn samples(
        &self,
        (x, y): (u32, u32),
        first: Option<Vec3>,
        offsets: &[(f32, f32)],
        record: &mut impl Record,
    ) -> Vec3 {
        let n = offsets.len() + usize::from(first.is_some());
        // `Sum` for Vec3 is this fold from zero.
        let start = Vec3::ZERO + first.unwrap_or(Vec3::ZERO);
        let p = &self.prepared;
        let sum = offsets
            .iter()
            .map(|&(dx, dy)| {
                let ray = self.camera.ray(x as f32 + dx, y as f32 + dy);
                match (&self.tiles, self.motion) {
                    (Some(t), _) => trace_primary(p, &ray, (t, x, y), self.bound, record),
                    (None, Some(_)) => trace(p, &ray, self.bound, record),
                    (None, None) => {
                        let hit = p.closest(&ray, f32::INFINITY);
                        reference::shade(p, &ray, hit, (0, 1.0), self.bound, &mut Plain)
                    }
                }
            })
            .fold(start, |a, b| a + b);
        sum / n as f32
    }

    /// Traces pixel `at` into `px` at `offsets` after sample `first` (see
    /// [`Self::pixel`]): its motion cells and linear colour; its segments go to
    /// `segs`.
    pub(crate) fn put(
        &self,
        at: (u32, u32),
        px: &mut [u8],
        (first, offsets): (Option<Vec3>, &[(f32, f32)]),
        segs: &mut Vec<Seg>,
    ) -> (Cells, Vec3) {
        let (c, mask) = self.pixel(at, first, offsets, segs);
        px.copy_from_slice(&[srgb8(c.x), srgb8(c.y), srgb8(c.z), 255]);
        (mask, c)
    }

    /// The shadow casters and footprints, taken out for the next frame
    /// ([`Kept`]).
    pub(crate) fn take_culling(&mut self) -> Option<(Vec<Option<Casters>>, Option<PerPlane>)> {
        let footprints = self.prepared.take_footprints();
        Some((self.prepared.take_casters()?, footprints))
    }

    /// Adaptive anti-aliasing's edge threshold (a byte difference), if on.
    pub(crate) fn edge(&self) -> Option<f32> {
        self.edge
    }

    /// Picture height (px).
    pub(crate) fn height(&self) -> u32 {
        self.height
    }

    /// Picture width (px).
    pub(crate) fn width(&self) -> u32 {
        self.width
    }

    /// The pixel's sample offsets.
    pub(crate) fn offsets(&self) -> &[(f32, f32)] {
        &self.offsets
    }

    /// The packet tracer for samples at `offsets`: centre samples with tiles.
    pub(crate) fn packets(&self, offsets: &[(f32, f32)]) -> Option<Packet<'_, 'a>> {
        let tiles = self
            .tiles
            .as_ref()
            .filter(|_| self.packets && offsets == [(0.5, 0.5)])?;
        Some(Packet::new(
            (&self.prepared, &self.camera, tiles),
            self.bound,
            LaneNotes::new(self.motion),
        ))
    }

    /// Traces a whole row with `offsets`; returns each pixel's motion cells and
    /// segments in a tracked frame (else an empty record). Centre samples go in packets
    /// where the tile allows. With `lin`, each pixel's linear colour goes there.
    pub(crate) fn row_with(
        &self,
        y: u32,
        out: &mut [u8],
        offsets: &[(f32, f32)],
        mut lin: Option<&mut [Vec3]>,
    ) -> RowMotion {
        let track = self.motion.is_some();
        let mut rm = RowMotion::new(self.width as usize, track);
        let packets = self.packets(offsets);
        let mut x = 0;
        while x < self.width {
            let lanes = LANES as u32;
            if let Some(pk) = &packets
                && x + lanes <= self.width
            {
                let span = &mut out[x as usize * 4..(x + lanes) as usize * 4];
                let done = pk.run(x, y, span);
                if let Some(l) = lin.as_deref_mut() {
                    for i in (0..LANES).filter(|i| done & (1 << i) != 0) {
                        l[x as usize + i] = pk.color(i);
                    }
                }
                if done == 0xFF && !track {
                    // All eight written, nothing to note.
                    x += lanes;
                    continue;
                }
                let marks = if track { pk.notes.marks() } else { [0; LANES] };
                for i in x..x + lanes {
                    rm.begin(track);
                    if done & (1 << (i - x)) != 0 {
                        if track {
                            rm.cells[i as usize] = marks[(i - x) as usize];
                            rm.segs.extend_from_slice(&pk.notes.lane((i - x) as usize));
                        }
                        continue;
                    }
                    let px = &mut out[i as usize * 4..i as usize * 4 + 4];
                    let (cells, c) = self.put((i, y), px, (None, offsets), &mut rm.segs);
                    if track {
                        rm.cells[i as usize] = cells;
                    }
                    if let Some(l) = lin.as_deref_mut() {
                        l[i as usize] = c;
                    }
                }
                x += lanes;
                continue;
            }
            rm.begin(track);
            let px = &mut out[x as usize * 4..x as usize * 4 + 4];
            let (cells, c) = self.put((x, y), px, (None, offsets), &mut rm.segs);
            if track {
                rm.cells[x as usize] = cells;
            }
            if let Some(l) = lin.as_deref_mut() {
                l[x as usize] = c;
            }
            x += 1;
        }
        rm.begin(track);
        rm.seal();
        rm.room();
        rm
    }

    /// Whether pixel `(x, y)` of a one-sample picture differs from a 4-neighbour
    /// by more than the edge threshold in some channel, given the least byte
    /// difference above it ([`least_above`]). The three channels are compared
    /// at once, each in a 16-bit lane of a word ([`spread`]): with `M` the top
    /// bit of each lane, `(a | M) - (b + least)` keeps a lane's top bit exactly
    /// where `a - b >= least` (the lanes' values stay within 510 of `M`, so
    /// nothing borrows across lanes), and the same with `a` and `b` swapped.
    pub(crate) fn is_edge(&self, base: &[u8], x: u32, y: u32, least: u16) -> bool {
        if least > 255 {
            return false;
        }
        let w = self.width as usize;
        let i = (y as usize * w + x as usize) * 4;
        let at = |j: usize| {
            let p = &base[j..j + 3];
            spread([p[0], p[1], p[2]])
        };
        let l = spread([least as u8; 3]);
        let here = at(i);
        let (here_m, here_l) = ((here | TOPS) - l, here + l);
        let differs = |j: usize| {
            let there = at(j);
            ((here_m - there) | ((there | TOPS) - here_l)) & TOPS != 0
        };
        (x > 0 && differs(i - 4))
            || (x + 1 < self.width && differs(i + 4))
            || (y > 0 && differs(i - 4 * w))
            || (y + 1 < self.height && differs(i + 4 * w))
    }

    /// [`Self::is_edge`] of every pixel of row `y`, at threshold `edge`
    /// ([`Self::edge_run`] of the whole row).
    pub(crate) fn edge_row(&self, base: &[u8], y: u32, edge: f32) -> Vec<bool> {
        let mut out = Vec::new();
        let least = least_above(edge);
        self.edge_run(
            base,
            (y, 0..self.width as usize),
            least,
            (&mut out, &mut Edges::default()),
        );
        out
    }

    /// Into `out` (emptied first), [`Self::is_edge`] of pixels `xs` of row
    /// `y` (within the picture), given the least byte difference above the
    /// threshold as there: byte by byte over the run and a pixel either side
    /// (a flag per byte: its difference from the byte of the pixel above,
    /// below, left or right counts), then each pixel's three colour bytes'
    /// flags together. Plain loops with no table and no branch, which the
    /// compiler does sixteen bytes at a time; `scratch` keeps their buffers.
    pub(crate) fn edge_run(
        &self,
        base: &[u8],
        (y, xs): (u32, std::ops::Range<usize>),
        least: u16,
        (out, scratch): (&mut Vec<bool>, &mut Edges),
    ) {
        out.clear();
        // Above 255 no byte difference counts: no edges.
        let Ok(least) = u8::try_from(least) else {
            out.resize(xs.len(), false);
            return;
        };
        let w = self.width as usize;
        // The run with its neighbours in the row.
        let (a, b) = (xs.start.saturating_sub(1), (xs.end + 1).min(w));
        let row = |y: u32| &base[(y as usize * w + a) * 4..(y as usize * w + b) * 4];
        let here = row(y);
        let Edges { flags, pairs } = scratch;
        flags.clear();
        flags.resize(here.len(), 0);
        let up = y.checked_sub(1);
        let down = (y + 1 < self.height).then_some(y + 1);
        for there in [up, down].into_iter().flatten().map(row) {
            for ((f, p), q) in flags.iter_mut().zip(here).zip(there) {
                *f |= u8::from(p.abs_diff(*q) >= least);
            }
        }
        // Each pair of a pixel and its right neighbour, byte by byte: the
        // flag goes to both.
        let right = &here[4.min(here.len())..];
        pairs.clear();
        pairs.extend(
            here.iter()
                .zip(right)
                .map(|(p, q)| u8::from(p.abs_diff(*q) >= least)),
        );
        for (f, p) in flags.iter_mut().zip(pairs.iter()) {
            *f |= p;
        }
        for (f, p) in flags[4.min(here.len())..].iter_mut().zip(pairs.iter()) {
            *f |= p;
        }
        // A pixel's colour bytes, not its alpha.
        out.extend(
            flags.as_chunks::<4>().0[xs.start - a..xs.end - a]
                .iter()
                .map(|f| u32::from_le_bytes(*f) & 0x00ff_ffff != 0),
        );
    }
}

/// The buffers of [`Frame::edge_run`], kept from run to run.
#[derive(Debug, Default)]
pub(crate) struct Edges {
    flags: Vec<u8>,
    pairs: Vec<u8>,
}

/// The top bit of each of the three 16-bit lanes of [`spread`].
const TOPS: u64 = 0x0000_8000_8000_8000;

/// Three bytes, each in a 16-bit lane of a word (the first lowest).
fn spread(c: [u8; 3]) -> u64 {
    u64::from(c[0]) | u64::from(c[1]) << 16 | u64::from(c[2]) << 32
}

/// The least byte difference `d` with `f32::from(d) > edge` (256 when none
/// is): a channel differs by more than `edge` where its difference is at
/// least this, so [`Frame::is_edge`] compares bytes.
pub(crate) fn least_above(edge: f32) -> u16 {
    (0..=255u8)
        .find(|&d| f32::from(d) > edge)
        .map_or(256, u16::from)
}

#[cfg(test)]
mod tests {
    use super::{Edges, Frame, RenderOptions, least_above};
    use crate::scene::Scene;

    /// A row's edge flags, and a run's, are each pixel's own edge test, on pictures of
    /// noise and of flat runs, at thresholds at, between and past the byte
    /// steps, and on pictures one pixel wide or high.
    #[test]
    fn a_rows_edges_are_each_pixels_edge_test() {
        let mut seed = 7u32;
        let mut next = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 24) as u8
        };
        for (w, h) in [(23, 17), (1, 9), (9, 1), (1, 1)] {
            let scene = Scene {
                size: (w, h),
                samples: 4,
                adaptive: Some(0.1),
                ..Scene::default()
            };
            let frame = Frame::new(&scene, RenderOptions::FULL, false);
            for flat in [false, true] {
                // Flat: runs of one colour, with steps of 0 to 3 between them.
                let base: Vec<u8> = (0..w * h * 4)
                    .map(|i| if flat { (i / 4 / 5 % 4) as u8 } else { next() })
                    .collect();
                // Some channel of a 4-neighbour differs by more than `edge`.
                let px = |x: u32, y: u32| &base[((y * w + x) * 4) as usize..][..3];
                let edge_at = |x: u32, y: u32, edge: f32| {
                    let n = [(-1, 0), (1, 0), (0, -1), (0, 1)];
                    n.iter().any(|&(dx, dy)| {
                        let (nx, ny) = (i64::from(x) + dx, i64::from(y) + dy);
                        (0..i64::from(w)).contains(&nx)
                            && (0..i64::from(h)).contains(&ny)
                            && px(x, y)
                                .iter()
                                .zip(px(nx as u32, ny as u32))
                                .any(|(a, b)| (f32::from(*a) - f32::from(*b)).abs() > edge)
                    })
                };
                for edge in [-1.0, 0.0, 0.5, 1.0, 2.0, 25.5, 254.9, 255.0, f32::NAN] {
                    for y in 0..h {
                        let want: Vec<bool> = (0..w).map(|x| edge_at(x, y, edge)).collect();
                        let row = frame.edge_row(&base, y, edge);
                        assert_eq!(row, want, "{w}x{h} flat {flat} edge {edge} row {y}");
                        let least = least_above(edge);
                        let one: Vec<bool> =
                            (0..w).map(|x| frame.is_edge(&base, x, y, least)).collect();
                        assert_eq!(one, want, "{w}x{h} flat {flat} edge {edge} row {y}");
                        // Every run of the row on its own.
                        let (mut run, mut scratch) = (Vec::new(), Edges::default());
                        for x0 in 0..w as usize {
                            for x1 in x0 + 1..=w as usize {
                                let at = (y, x0..x1);
                                frame.edge_run(&base, at, least, (&mut run, &mut scratch));
                                assert_eq!(run, want[x0..x1], "{w}x{h} {edge} row {y} {x0}..{x1}");
                            }
                        }
                    }
                }
            }
        }
    }
}
