//! What moved since the last frame, and which pixels of a row it may have
//! changed: the motion filter of incremental frames (cells and the screen's
//! runs first, `screen`, then the segments of the pixels they leave, eight at a
//! time, against the moved shapes).

use super::Spans;
use crate::bits::BitRoom;
use crate::motion::{BLOCK, RowMotion, SUPER};
use crate::motion::{Batch, Cells, HITS, MET, Near, NearSet, SHADOW, Seg, point_segment};
use crate::simd::{Build, Kernel, Simd};
use crate::tuning::BLOCKS_AHEAD;
use glam::Vec3;

mod masks;
use masks::{BLOCK_SHIFT, SUPER_SHIFT, flags, meeting, run_bits, skip_ended};

/// What moved since the last frame: the cells of the moved objects, where they
/// were and where they are, and those shapes grown a little.
#[derive(Debug, Clone, Default)]
pub(crate) struct Moved {
    pub(crate) cells: Cells,
    /// Each shape with its own cells.
    pub(crate) near: NearSet,
    /// The box around every `near`.
    pub(crate) lo: Vec3,
    pub(crate) hi: Vec3,
    /// A moved shape has no [`crate::motion::Near`] (a plane): the cells alone
    /// decide.
    pub(crate) coarse: bool,
    /// Per row, where the moved shapes may meet pixels' free segments, which
    /// leave no cells (`Record::segment`'s `free`).
    pub(crate) spans: Spans,
    /// The moved balls: where each was and is, its radius, and its
    /// [`SHADOW`] bit.
    pub(crate) balls: Vec<(Vec3, Vec3, f32, Cells)>,
    /// The [`SHADOW`] bits of the moved balls that no other ball shares: a
    /// blocked shadow ray that names one of them was blocked by that ball
    /// where it was, so its new place alone decides
    /// ([`Batch::test_blocked`]).
    pub(crate) sole: Cells,
    /// The [`MET`] bits of the moved objects that no object that stayed
    /// shares: a pixel with one is taken at once.
    pub(crate) sure: Cells,
    /// The moved objects where they were whose bits an object that stayed
    /// shares, each with its bit: a pixel with such a bit is taken where one
    /// of its segments comes near one of them.
    pub(crate) was: Vec<(Cells, Near)>,
}

/// Which of a row's records [`Moved::dirty`] reads.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Layer<'a> {
    /// The base layer: a pixel's centre sample, every pixel recorded.
    Base,
    /// The edge layer: the other samples of the pixels that are edges, `is`
    /// (the row's edge flags; the others hold no record), and the pixels
    /// `taken`, whose base sample is traced again.
    Edges { is: &'a [bool], taken: &'a [u32] },
}

impl Moved {
    /// Whether the moved shapes may reach a pixel of row `y`, whose record is
    /// `rm` (sealed).
    pub(crate) fn reaches(&self, y: usize, rm: &RowMotion) -> bool {
        rm.meets(self.cells) || !self.spans.row(y).is_empty()
    }

    /// Into `out` (emptied first), the pixels of row `y`, whose record is `rm`
    /// (sealed), that may have changed, in order; false when no pixel may. A
    /// pixel may have changed when one of its rays met a moved object where
    /// it was (its [`MET`] bits: taken at once where no object that stayed
    /// shares the bit, [`Self::sure`], else where one of its segments comes
    /// near a moved object's old place, [`Self::was`]); when a shadow ray of it was
    /// blocked by a moved ball (its [`SHADOW`] bits) and that ray's flagged
    /// segment may be blocked no more ([`Self::met_ball_before`],
    /// [`Batch::test_blocked`]); or when its cells
    /// meet the moved ones or it lies in the row's [`Spans`], and (in a
    /// tracked record of a frame without a moved plane) one of its other
    /// segments near the moved shapes' box comes within a moved shape where
    /// it is now, whose cells meet its own, or any moved shape for a pixel in
    /// the spans ([`crate::motion::Near::meets`]; out of the spans, not its
    /// leading free segments, [`Seg::free`]). Where a moved object was
    /// matters only to the rays that met it, and those carry its bit. Blocks
    /// none of this reaches are skipped whole; the segments are tested eight
    /// at a time ([`Batch`]). With
    /// `sure`, a pixel in the row's sure runs ([`Spans::sure_row`]: its centre
    /// well inside a moved ball's image) is taken without its segments: its
    /// centre ray meets the ball unless something hides it, and a pixel taken
    /// needlessly is only traced again, so the frame keeps its bytes either
    /// way (the base layer, one centre sample, asks for it; the edge layer's
    /// samples lie anywhere in the pixel and each costs three, so it does not).
    /// In the edge layer ([`Layer::Edges`]) only edge pixels are read and go
    /// to `out`: those of the pixels `taken` (ascending: those the caller
    /// traces again anyway) as they are, their segments not tested.
    pub(crate) fn dirty(
        &self,
        y: usize,
        rm: &RowMotion,
        layer: Layer<'_>,
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        if !self.reaches(y, rm) {
            if let Layer::Edges { is, taken } = layer {
                out.extend(edges_among(is, taken));
            }
            return !out.is_empty();
        }
        Build::detect().run(Dirty {
            moved: self,
            at: (y, rm, layer),
            out,
        })
    }

    /// [`Self::dirty`] after its row test, in lane build `s`, for the edge
    /// layer where `EDGES` (`is`, `taken`: [`Layer::Edges`]), else the base
    /// layer (each built apart, so that the base layer's walk has no test of
    /// edge flags).
    #[expect(
        clippy::inline_always,
        reason = "inlined into each build, so the AVX2 one compiles it for AVX2"
    )]
    #[inline(always)]
    fn dirty_with<S: Simd, const EDGES: bool>(
        &self,
        s: S,
        (y, rm, is, taken): (usize, &RowMotion, &[bool], &[u32]),
        out: &mut Vec<u32>,
    ) -> bool {
        let n = rm.cells.len();
        let mut room = BitRoom::new();
        let mut hit = room.row(n);
        // A pixel already in `hit` has its segments skipped (only edges
        // hold segments here, and only edges go out).
        for x in edges_among(is, taken) {
            hit.set(x as usize);
        }
        let mut batch = (Batch::default(), Batch::default());
        let runs = self.spans.row(y);
        let sure = if EDGES { &[] } else { self.spans.sure_row(y) };
        // The first run that ends after the pixel at hand (pixels ascend).
        let (mut r, mut sr) = (0, 0);
        let cells_only = !rm.tracked() || self.coarse;
        // The blocks whose candidates are read next, in a ring: the walk is
        // `BLOCKS_AHEAD` blocks ahead of the reading (`planned` of them so
        // far).
        let (mut ahead, mut planned) = ([Plan::NONE; BLOCKS_AHEAD], 0);
        // Eight super-blocks at a time: those whose cells meet the moved ones
        // or that a run touches.
        for (g, eight) in rm.supers.chunks(SUPER).enumerate() {
            let s0 = g * SUPER;
            let x0 = s0 * SUPER * BLOCK;
            skip_ended(runs, &mut r, x0);
            let pixels = x0..(x0 + SUPER * SUPER * BLOCK).min(n);
            let mut supers =
                meeting(s, eight, self.cells) | run_bits::<SUPER_SHIFT>(&runs[r..], &pixels);
            while supers != 0 {
                let i = s0 + supers.trailing_zeros() as usize;
                supers &= supers - 1;
                let (b0, b1) = (i * SUPER, ((i + 1) * SUPER).min(rm.blocks.len()));
                let xs = b0 * BLOCK..(b1 * BLOCK).min(n);
                skip_ended(runs, &mut r, xs.start);
                // The super-block's blocks whose cells meet the moved ones, and
                // those a run meets.
                let mut blocks = meeting(s, &rm.blocks[b0..b1], self.cells)
                    | run_bits::<BLOCK_SHIFT>(&runs[r..], &xs);
                while blocks != 0 {
                    let b = b0 + blocks.trailing_zeros() as usize;
                    blocks &= blocks - 1;
                    let (x0, x1) = (b * BLOCK, ((b + 1) * BLOCK).min(n));
                    // The block's pixels that hold a record: in the edge layer
                    // only its edges.
                    let held = if EDGES { flags(&is[x0..x1]) } else { u32::MAX };
                    if held == 0 {
                        continue;
                    }
                    skip_ended(runs, &mut r, x0);
                    let plan =
                        self.plan::<S, EDGES>(s, (rm, x0..x1, held), &runs[r..], (sure, &mut sr));
                    if plan.cands == 0 {
                        continue;
                    }
                    // The block's segments are on their way while the blocks
                    // before are read (every pixel's: the segments of a
                    // pixel and of the next lie side by side, so a
                    // candidate's that reach past its first cache line come
                    // too).
                    if !cells_only {
                        rm.prefetch(s, x0);
                    }
                    let first = std::mem::replace(&mut ahead[planned % BLOCKS_AHEAD], plan);
                    planned += 1;
                    if first.cands != 0 {
                        self.block::<S, EDGES>(s, rm, first, (&mut batch, &mut hit));
                    }
                }
            }
        }
        for j in 0..BLOCKS_AHEAD {
            let p = ahead[(planned + j) % BLOCKS_AHEAD];
            if p.cands != 0 {
                self.block::<S, EDGES>(s, rm, p, (&mut batch, &mut hit));
            }
        }
        batch.0.test(s, &self.near, &mut hit);
        batch.1.test_blocked(s, &self.balls, &mut hit);
        out.extend(hit.iter().map(|k| k as u32));
        !out.is_empty()
    }

    /// The candidates among pixels `xs` of `rm` (a block; those of them whose
    /// bit `k - xs.start` of `held` is set): those whose cells meet the moved
    /// ones or that lie in one of `runs` (the first of them ends after
    /// `xs.start`); `sr`: the first of `sure` that ends after `xs.start`
    /// once moved on, kept so for the next block.
    #[expect(
        clippy::inline_always,
        reason = "inlined into each build, so the AVX2 one compiles it for AVX2"
    )]
    #[inline(always)]
    fn plan<S: Simd, const EDGES: bool>(
        &self,
        s: S,
        (rm, xs, held): (&RowMotion, std::ops::Range<usize>, u32),
        runs: &[(u32, u32)],
        (sure, sr): (&[(u32, u32)], &mut usize),
    ) -> Plan {
        // The block's pixels in a run, where any moved shape may meet a free
        // segment.
        let in_runs = run_bits::<0>(runs, &xs);
        // Those in a sure run (none in the edge layer).
        let in_sure = if EDGES {
            0
        } else {
            skip_ended(sure, sr, xs.start);
            run_bits::<0>(&sure[*sr..], &xs)
        };
        let cands = (meeting(s, &rm.cells[xs.clone()], self.cells) | in_runs) & held;
        Plan {
            x0: xs.start as u32,
            cands: cands as u8,
            in_runs: in_runs as u8,
            in_sure: in_sure as u8,
        }
    }

    /// Reads the candidates of `plan` (a block of `rm`): their segments
    /// tested in `batch`, the pixels met noted in `hit`.
    #[expect(
        clippy::inline_always,
        reason = "inlined into each build, so the AVX2 one compiles it for AVX2"
    )]
    #[inline(always)]
    fn block<S: Simd, const EDGES: bool>(
        &self,
        s: S,
        rm: &RowMotion,
        plan: Plan,
        ((batch, blocked), hit): (&mut (Batch, Batch), &mut crate::bits::RowBits<'_>),
    ) {
        let cells_only = !rm.tracked() || self.coarse;
        let Plan {
            x0,
            mut cands,
            in_runs,
            in_sure,
        } = plan;
        while cands != 0 {
            let bit = cands.trailing_zeros() as usize;
            cands &= cands - 1;
            let k = x0 as usize + bit;
            let in_run = in_runs >> bit & 1 != 0;
            let own = rm.cells[k] & self.cells;
            // The moved balls (or those sharing their bits) that blocked a
            // shadow ray of the pixel.
            let mut shadow = 0;
            if own & HITS != 0 {
                // A ray of the pixel met a moved object where it was.
                let met = own & MET;
                if met != 0
                    && (cells_only
                        || met & self.sure != 0
                        || rm.of(k).iter().any(|seg| self.met_before(seg, met)))
                {
                    hit.set(k);
                    continue;
                }
                shadow = own & SHADOW;
            }
            let cells = if in_run {
                Cells::MAX & !HITS
            } else {
                own & !HITS
            };
            if cells == 0 && shadow == 0 {
                continue;
            }
            if cells_only {
                hit.set(k);
                continue;
            }
            if in_sure >> bit & 1 != 0 {
                hit.set(k);
                continue;
            }
            // (In the edge layer a pixel `taken` is in `hit` already.)
            if EDGES && hit.has(k) {
                continue;
            }
            // Where each of the pixel's hit bits is one of `sole`, a blocked
            // shadow ray's blocker is a moved ball, and that ball where it
            // was met it: it blocked the ray when the pixel was traced, and
            // in each frame since that it moved, the ray passed well through
            // it, or the pixel was traced again.
            let sole = shadow != 0 && rm.cells[k] & HITS & !self.sole == 0;
            // A pixel's free segments come first (its camera ray's, then
            // those of a camera ray that met a plane), and meet a moved
            // shape only in the row's runs ([`Spans`]): out of them, they
            // are not read, up to the first with a flag (a blocked shadow
            // ray's, which its blocker's moving away changes wherever the
            // pixel lies).
            let mut segs = rm.of(k);
            if !in_run {
                while let [first, rest @ ..] = segs
                    && first.free()
                    && !first.flagged()
                {
                    segs = rest;
                }
            }
            for seg in segs {
                if seg.flagged() {
                    // A blocked shadow ray that met a moved ball of the
                    // pixel's where it was: their new places decide, eight
                    // rays at a time ([`Batch::test_blocked`]).
                    let met = shadow != 0 && (sole || self.met_ball_before(seg, shadow));
                    if met && blocked.push(k as u32, shadow, seg) {
                        blocked.test_blocked(s, &self.balls, hit);
                        if hit.has(k) {
                            break;
                        }
                    }
                    continue;
                }
                if cells == 0 {
                    continue;
                }
                let near_box =
                    seg.a.max(seg.b).cmpge(self.lo).all() && seg.a.min(seg.b).cmple(self.hi).all();
                // A full batch is tested at once, which may take the pixel.
                if near_box && batch.push(k as u32, cells, seg) {
                    batch.test(s, &self.near, hit);
                    if hit.has(k) {
                        break;
                    }
                }
            }
        }
    }
}

impl Moved {
    /// Whether `seg` comes near one of the moved objects where they were
    /// whose bits are among `met` ([`Self::was`]).
    fn met_before(&self, seg: &Seg, met: Cells) -> bool {
        (self.was.iter()).any(|(bit, n)| bit & met != 0 && n.meets(seg))
    }

    /// Whether the blocked shadow ray of `seg` (flagged) meets a moved ball
    /// of the pixel's `shadow` bits where it was: then it may be blocked no
    /// more, unless it passes well through one of those balls where they are
    /// ([`Batch::test_blocked`]). Only those balls: a pixel kept because its
    /// ray passes through another ball would keep a record that names a
    /// blocker no longer in the way, and miss that ball leaving later.
    fn met_ball_before(&self, seg: &Seg, shadow: Cells) -> bool {
        (self.balls.iter()).any(|&(c0, _, r, bit)| {
            bit & shadow != 0 && point_segment(c0, seg.a, seg.b) <= r + Near::PAD
        })
    }
}

/// A block's candidates for [`Moved::block`], found by [`Moved::plan`].
#[derive(Debug, Clone, Copy)]
struct Plan {
    /// The block's first pixel.
    x0: u32,
    /// Bit `k - x0` for each candidate pixel `k` (none: no block).
    cands: u8,
    /// The pixels in a run, and in a sure run.
    in_runs: u8,
    in_sure: u8,
}

impl Plan {
    /// No block.
    const NONE: Self = Self {
        x0: 0,
        cands: 0,
        in_runs: 0,
        in_sure: 0,
    };
}

/// The pixels of `taken` that are edges (`is`), in their order.
fn edges_among<'a>(is: &'a [bool], taken: &'a [u32]) -> impl Iterator<Item = u32> + 'a {
    taken.iter().copied().filter(|&x| is[x as usize])
}

/// [`Moved::dirty`] after its row test, as a lane kernel.
struct Dirty<'k> {
    moved: &'k Moved,
    at: (usize, &'k RowMotion, Layer<'k>),
    out: &'k mut Vec<u32>,
}

#[expect(
    clippy::inline_always,
    reason = "a kernel inlines into its build's entry point, which compiles it for AVX2 in the AVX2 build"
)]
impl Kernel for Dirty<'_> {
    type Output = bool;
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> bool {
        let (y, rm, layer) = self.at;
        match layer {
            Layer::Base => self
                .moved
                .dirty_with::<S, false>(s, (y, rm, &[], &[]), self.out),
            Layer::Edges { is, taken } => {
                self.moved
                    .dirty_with::<S, true>(s, (y, rm, is, taken), self.out)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Layer, Moved};
    use crate::motion::{Cells, Near, NearSet, RowMotion, Seg};
    use crate::scene::Shape;
    use glam::Vec3;

    /// The hit bit of the moving object of rank `r` (`moving_bits`).
    fn met(r: u32) -> Cells {
        1 << (64 + r)
    }

    /// The moved ball of rank 0 and radius 0.02 m, from `c0` to `c1`: its hit
    /// and shadow bits, no cells of the grid.
    fn ball_moved(c0: Vec3, c1: Vec3) -> Moved {
        Moved {
            cells: met(0) | met(0) << 32,
            near: NearSet::new(Vec::new()),
            lo: Vec3::INFINITY,
            hi: Vec3::NEG_INFINITY,
            balls: vec![(c0, c1, 0.02, met(0) << 32)],
            sure: met(0),
            ..Moved::default()
        }
    }

    /// A tracked row of pixels, each with its cells and segments.
    fn row(pixels: &[(Cells, Vec<Seg>)]) -> RowMotion {
        let mut rm = RowMotion::new(pixels.len(), true);
        for (k, (cells, segs)) in pixels.iter().enumerate() {
            rm.begin(true);
            rm.cells[k] = *cells;
            rm.segs.extend_from_slice(segs);
        }
        rm.begin(true);
        rm.seal();
        rm
    }

    /// The pixels of `rm` that `moved` takes.
    fn taken(moved: &Moved, rm: &RowMotion) -> Vec<u32> {
        let mut out = Vec::new();
        moved.dirty(0, rm, Layer::Base, &mut out);
        out
    }

    /// A blocked shadow ray's segment along y through the origin, 0.2 m long.
    fn shadow_through_origin() -> Seg {
        let mut s = Seg {
            a: Vec3::new(0.0, -0.1, 0.0),
            b: Vec3::new(0.0, 0.1, 0.0),
        };
        s.flag();
        s
    }

    /// [`shadow_through_origin`] 5 cm along x, flagged.
    fn shadow_aside() -> Seg {
        let mut s = shadow_through_origin();
        s.a.x += 0.05;
        s.b.x += 0.05;
        s.flag();
        s
    }

    #[test]
    fn a_pixel_whose_ray_met_a_moved_object_is_taken_without_its_segments() {
        let moved = ball_moved(Vec3::ZERO, Vec3::new(0.001, 0.0, 0.0));
        // Met the moved ball; met a moving object that did not move this
        // time; met nothing that moves.
        let rm = row(&[(met(0), vec![]), (met(1), vec![]), (0, vec![])]);
        assert_eq!(taken(&moved, &rm), [0]);
    }

    /// The edge layer gives edge pixels only: those of the pixels taken in
    /// the base layer, and those its own records take.
    #[test]
    fn the_edge_layer_gives_only_edges() {
        let moved = ball_moved(Vec3::ZERO, Vec3::new(0.001, 0.0, 0.0));
        let is = [true, false, true, false, true];
        let edges = |rm: &RowMotion, taken: &[u32]| {
            let mut out = Vec::new();
            moved.dirty(0, rm, Layer::Edges { is: &is, taken }, &mut out);
            out
        };
        // No record meets the moved ones: the taken edges alone.
        let quiet = row(&vec![(0, vec![]); 5]);
        assert_eq!(edges(&quiet, &[0, 1, 3]), [0]);
        assert!(edges(&quiet, &[1, 3]).is_empty());
        // Pixels 2 and 3 met the moved ball; 3 is no edge.
        let met_it = row(&[
            (0, vec![]),
            (0, vec![]),
            (met(0), vec![]),
            (met(0), vec![]),
            (0, vec![]),
        ]);
        assert_eq!(edges(&met_it, &[0, 1, 3]), [0, 2]);
    }

    #[test]
    fn a_shared_bit_takes_a_pixel_only_where_it_met_the_moved_object() {
        // Ball 0 moved; an object that stayed shares its bit, so the bit is
        // not sure, and its old place decides.
        let mut moved = ball_moved(Vec3::ZERO, Vec3::new(0.001, 0.0, 0.0));
        moved.sure = 0;
        let was = Shape::Sphere {
            centre: Vec3::ZERO,
            radius: 0.02,
        };
        moved.was = vec![(met(0), Near::of(&was).unwrap())];
        // A camera ray that ended on the ball where it was (its hit 3e-6 m
        // off the surface), and one that ended on the other object 10 cm
        // away.
        let on_it = Seg {
            a: Vec3::new(0.0, 0.0, 0.5),
            b: Vec3::new(0.0, 0.0, 0.020_003),
        };
        let elsewhere = Seg {
            a: Vec3::new(0.1, 0.0, 0.5),
            b: Vec3::new(0.1, 0.0, 0.02),
        };
        let rm = row(&[(met(0), vec![on_it]), (met(0), vec![elsewhere])]);
        assert_eq!(taken(&moved, &rm), [0]);
    }

    #[test]
    fn a_blocked_shadow_ray_is_traced_again_only_when_its_ball_leaves_it() {
        let shadow = met(0) << 32;
        // A ray blocked by the ball where it was, and one that passed 5 cm
        // from it (a pixel with the ball's shadow bit from another ray).
        let aside = shadow_aside();
        let rm = row(&[
            (shadow, vec![shadow_through_origin()]),
            (shadow, vec![aside]),
        ]);
        // Moved 10 cm away: the core's ray is lit again.
        let away = ball_moved(Vec3::ZERO, Vec3::new(0.1, 0.0, 0.0));
        assert_eq!(taken(&away, &rm), [0]);
        // Moved 2 mm: the ray still passes 18 mm deep through it.
        let still = ball_moved(Vec3::ZERO, Vec3::new(0.002, 0.0, 0.0));
        assert!(taken(&still, &rm).is_empty());
        // Moved onto the ray's end: no longer well through, so it may be lit.
        let edge = ball_moved(Vec3::ZERO, Vec3::new(0.0, 0.095, 0.0));
        assert_eq!(taken(&edge, &rm), [0]);
        // Moved away while another moved ball (bit 1, not the pixel's) came
        // to lie across the ray: traced again, so its record names the new
        // blocker.
        let mut other = away.clone();
        other.cells |= met(1) | met(1) << 32;
        other
            .balls
            .push((Vec3::new(0.3, 0.0, 0.0), Vec3::ZERO, 0.02, met(1) << 32));
        assert_eq!(taken(&other, &rm), [0]);
        // Without the ball's shadow bit a flagged segment is not read.
        let rm = row(&[(0, vec![shadow_through_origin()])]);
        assert!(taken(&away, &rm).is_empty());
    }

    #[test]
    fn a_sole_ball_bit_passes_over_the_old_place_only_where_it_is_the_pixels_every_bit() {
        let shadow = met(0) << 32;
        // Ball 0 holds its bit alone: a ray that names it was blocked by it.
        let mut away = ball_moved(Vec3::ZERO, Vec3::new(0.1, 0.0, 0.0));
        away.sole = shadow;
        let aside = shadow_aside();
        // The core's ray is lit again; so is any ray that names only the
        // ball (it passes well through the ball where it is no more).
        let rm = row(&[
            (shadow, vec![shadow_through_origin()]),
            (shadow, vec![aside]),
        ]);
        assert_eq!(taken(&away, &rm), [0, 1]);
        // A pixel that also names a string (bit 1, still) that blocked the
        // ray 5 cm from the ball: the ball's old place decides, and it never
        // met the ray.
        let rm = row(&[(shadow | met(1), vec![aside])]);
        assert!(taken(&away, &rm).is_empty());
        // Moved 2 mm: the core's ray still passes well through it.
        let mut still = ball_moved(Vec3::ZERO, Vec3::new(0.002, 0.0, 0.0));
        still.sole = shadow;
        let rm = row(&[(shadow, vec![shadow_through_origin()])]);
        assert!(taken(&still, &rm).is_empty());
    }

    #[test]
    fn a_free_segment_is_read_only_in_the_runs_unless_it_is_flagged() {
        use crate::retrace::Spans;
        // The ball now at the origin, in grid cell 0.
        let ball = Shape::Sphere {
            centre: Vec3::ZERO,
            radius: 0.02,
        };
        let near = Near::of(&ball).unwrap();
        let mut moved = Moved {
            cells: 1,
            near: NearSet::new(vec![(1, near)]),
            lo: near.lo(),
            hi: near.hi(),
            ..Moved::default()
        };
        // Along z through the centre, and 10 cm aside.
        let mut through = Seg {
            a: Vec3::new(0.0, 0.0, -0.1),
            b: Vec3::new(0.0, 0.0, 0.1),
        };
        let mut aside = through;
        aside.a.x += 0.1;
        aside.b.x += 0.1;
        let (mut free_through, mut free_aside) = (through, aside);
        free_through.set_free();
        free_aside.set_free();
        assert!(free_through.free() && !through.free());
        // A free segment through the ball out of the runs, the same in the
        // run, and a free segment aside before one with cells through it.
        let rm = row(&[
            (1, vec![free_through, aside]),
            (1, vec![free_through, aside]),
            (1, vec![free_aside, through]),
        ]);
        moved.spans = Spans::of_runs(vec![(0, 1, 2)], 1);
        assert_eq!(taken(&moved, &rm), [1, 2]);
        // A blocked shadow ray from a plane (free, flagged) is read wherever
        // the pixel lies: the ball that blocked it moved away.
        let mut blocked = shadow_through_origin();
        blocked.set_free();
        let away = ball_moved(Vec3::ZERO, Vec3::new(0.1, 0.0, 0.0));
        let rm = row(&[(met(0) << 32 | 1, vec![blocked])]);
        assert_eq!(taken(&away, &rm), [0]);
        // Cleared by the clip that makes a segment, as its other flag is.
        through.flag();
        through.set_free();
        let grid = crate::motion::MotionGrid::new(crate::geometry::Aabb {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        });
        let ray = crate::geometry::Ray {
            origin: through.a,
            dir: Vec3::Z,
        };
        let clipped = grid.clip(&ray, 0.2).unwrap();
        assert!(!clipped.free() && !clipped.flagged());
    }
}
