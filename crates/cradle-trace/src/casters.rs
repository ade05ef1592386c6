//! Shadow-ray casters of the bounded objects: for each object, light and piece
//! of its length, the objects that can lie between it and the light. A shadow
//! ray from an object tests only those ([`Prepared::occluded_towards`]), instead
//! of walking the hierarchy: the answer is a yes/no, so any superset of the
//! blockers in any order gives the same bits.
//!
//! [`Prepared::occluded_towards`]: super::prepared::Prepared::occluded_towards

use super::bvh::Bvh;
use super::geometry::Aabb;
use super::geometry::{Geom, bounds};
use super::scene::{Light, Shape};
use super::wide::{Chunk, WideList, push_chunks};
use glam::Vec3;

/// The bounded objects (in query order) that can block a shadow ray towards
/// `light` from a point of the object with box `from`.
///
/// Such a ray starts within `from` (lifted 2e-5 m off its surface) and runs to
/// the light (or, for a directional light, away along it), so every point of it is
/// within the box's half-diagonal, plus margins for the lift and for rounding,
/// of the segment from the box's centre to the light. An object can only block it
/// if its box, widened by that much, meets that segment. Ambient light casts no
/// shadow rays: no list.
///
/// With a hierarchy over `bounded` (`bvh` over their boxes, items its
/// positions), only the objects in the nodes near the segment are tested: many
/// objects then cost O(log n) each. The casters (object, box) go to `out`.
fn casters(
    from: Aabb,
    light: &Light,
    bounded: &[(usize, Aabb)],
    bvh: Option<(&Bvh, &[Aabb])>,
    out: &mut Vec<(usize, Aabb)>,
) {
    out.clear();
    let Some(reach) = Reach::new(from, light) else {
        return;
    };
    let meets = |b: &Aabb| reach.meets(b);
    match bvh {
        Some((bvh, boxes)) => {
            let mut ks = Vec::new();
            bvh.collect(meets, boxes, &mut ks);
            // Back to query order.
            ks.sort_unstable();
            out.extend(ks.into_iter().map(|k| bounded[k]));
        }
        None => out.extend(bounded.iter().filter(|(_, b)| meets(b))),
    }
}

/// Where a shadow ray towards a light from a point of a box can run: near the
/// segment from the box's centre to the light (or along a directional light),
/// within the box's half-diagonal and margins for the lift and for rounding
/// ([`casters`]). `None` for ambient light, which casts no shadow rays.
struct Reach {
    centre: Vec3,
    inv: Vec3,
    widen: f32,
    t_max: f32,
    /// A box outside which no box [`Self::meets`]: it holds every point
    /// within `widen` of the segment, padded far beyond the rounding of
    /// `meets`.
    bounds: Aabb,
}

impl Reach {
    fn new(from: Aabb, light: &Light) -> Option<Self> {
        let centre = (from.min + from.max) * 0.5;
        let (dir, t_max) = match *light {
            Light::Ambient { .. } => return None,
            // t in 0..=1 along the segment to the light.
            Light::Point { position, .. } => (position - centre, 1.0),
            Light::Directional { direction, .. } => (-direction, f32::INFINITY),
        };
        let reach = if t_max.is_finite() { dir.length() } else { 0.0 };
        let scale = centre.abs().max_element() + reach;
        let widen = 0.5 * (from.max - from.min).length() + 1e-4 + 1e-4 * scale;
        // The segment's far end: the light, or without end along each axis
        // the light's direction runs along.
        let end = if t_max.is_finite() {
            centre + dir
        } else {
            Vec3::select(dir.cmpeq(Vec3::ZERO), centre, dir.signum() * f32::INFINITY)
        };
        // Rounding in `meets` is some 1e-7 of the scale; the pad is a
        // thousand times that.
        let pad = Vec3::splat(widen + 1e-4 + 1e-4 * scale);
        Some(Self {
            centre,
            inv: dir.recip(),
            widen,
            t_max,
            bounds: Aabb {
                min: centre.min(end) - pad,
                max: centre.max(end) + pad,
            },
        })
    }

    /// Whether an object with box `b` can lie in the reach.
    fn meets(&self, b: &Aabb) -> bool {
        let t1 = (b.min - self.widen - self.centre) * self.inv;
        let t2 = (b.max + self.widen - self.centre) * self.inv;
        let near = t1.min(t2).max_element().max(0.0);
        let far = t1.max(t2).min_element().min(self.t_max);
        // NaN (an axis the segment runs along, at a slab's edge): keep it.
        near <= far || near.is_nan() || far.is_nan()
    }
}

/// The reaches of an object's pieces towards each light (`None` for ambient
/// light), each light's with the box holding them all.
struct Reaches(Vec<(Vec<Option<Reach>>, Aabb)>);

impl Reaches {
    fn of(shape: &Shape, lights: &[Light]) -> Self {
        let boxes = piece_boxes(shape);
        Self(
            (lights.iter())
                .map(|l| {
                    let reaches: Vec<_> = boxes.iter().map(|&b| Reach::new(b, l)).collect();
                    let all =
                        (reaches.iter().flatten()).fold(Aabb::EMPTY, |h, r| h.union(r.bounds));
                    (reaches, all)
                })
                .collect(),
        )
    }

    /// Whether no reach meets one of `boxes`. In a long row most objects'
    /// reaches pass far from the moved ones: the box holding all of an
    /// object's reaches towards a light is tested first, and only the boxes
    /// it meets are tested piece by piece.
    fn miss(&self, boxes: &[Aabb]) -> bool {
        let mut near = Vec::new();
        self.0.iter().all(|(reaches, all)| {
            near.clear();
            near.extend(boxes.iter().filter(|m| m.overlaps(all)));
            near.is_empty() || (reaches.iter().flatten()).all(|r| !near.iter().any(|m| r.meets(m)))
        })
    }
}

/// The boxes of a sphere or cylinder's pieces ([`Casters`]): a cylinder cut
/// along its axis into pieces about four radii long (at most 16), each box
/// holding its part of the shape and overlapping its neighbours' by a margin
/// far beyond the rounding of a piece lookup (and beyond the 2e-5 m that
/// shadow rays start off the caps); a sphere, or a plane, is one piece (its
/// box; none for a plane).
pub(crate) fn piece_boxes(shape: &Shape) -> Vec<Aabb> {
    let (a, b, radius) = match *shape {
        Shape::Plane { .. } => return Vec::new(),
        Shape::Sphere { centre, radius } => (centre, centre, radius),
        Shape::Cylinder { a, b, radius } => (a, b, radius),
    };
    let len = (b - a).length();
    let pieces = if len > 0.0 {
        ((len / (4.0 * radius)).ceil() as usize).clamp(1, 16)
    } else {
        1
    };
    if pieces == 1 {
        return bounds(shape).into_iter().collect();
    }
    let u = (b - a) / len;
    let margin = 1e-4 + 1e-4 * len;
    let step = len / pieces as f32;
    (0..pieces)
        .filter_map(|k| {
            let (s0, s1) = (k as f32 * step - margin, (k + 1) as f32 * step + margin);
            bounds(&Shape::Cylinder {
                a: a + u * s0,
                b: a + u * s1,
                radius: radius + margin,
            })
        })
        .collect()
}

/// The casters of one object's shadow rays, per light, per piece of its length:
/// a cylinder is cut along its axis into pieces about four radii long (at most
/// 16), so that a shadow ray from a point of a long rod tests only what can lie
/// between that part of the rod and the light. A sphere is one piece.
#[derive(Debug, Clone)]
pub(crate) struct Casters {
    /// Start of the axis, unit axis and length (m); pieces along it.
    a: Vec3,
    u: Vec3,
    len: f32,
    pieces: usize,
    /// Lights (ambient ones with empty lists).
    lights: usize,
    /// Every list's boxes, eight at a time, one list after another.
    chunks: Vec<Chunk>,
    /// Per light, per piece (`light * pieces + piece`): where in `chunks` the
    /// objects (in query order) that can block are, with the object itself
    /// (`[0]..[1]`) and without it (`[1]..[2]`): two lists, one after the
    /// other.
    ranges: Vec<[u32; 3]>,
}

impl Casters {
    /// The casters of object `me` with `shape` for each of `lights`; `None`
    /// for planes.
    ///
    /// Each list comes with and without the object itself. A shadow ray from a
    /// point its ray met from outside cannot meet the object: it is traced only
    /// where the light is on the outer side (`lambert > 0`), starting 2e-5 m off
    /// the surface along the outward normal, so it runs away from the tangent
    /// plane there, and a sphere or capped cylinder (convex) lies wholly on the
    /// other side of it, 2e-5 m (a hundred times the f32 rounding at a metre)
    /// away at least. A ray that met it from inside (a reflection starting
    /// within a touching ball) turns the normal inwards: then it can.
    pub(crate) fn new(
        (me, shape): (usize, &Shape),
        lights: &[Light],
        bounded: &[(usize, Aabb)],
        bvh: Option<(&Bvh, &[Aabb])>,
    ) -> Option<Self> {
        let (a, b) = match *shape {
            Shape::Plane { .. } => return None,
            Shape::Sphere { centre, .. } => (centre, centre),
            Shape::Cylinder { a, b, .. } => (a, b),
        };
        let len = (b - a).length();
        let boxes = piece_boxes(shape);
        let pieces = boxes.len();
        let u = if len > 0.0 { (b - a) / len } else { Vec3::ZERO };
        // Most lists fill a chunk, with the object and without.
        let mut chunks = Vec::with_capacity(2 * lights.len() * pieces);
        let mut ranges = Vec::with_capacity(lights.len() * pieces);
        let mut found = Vec::new();
        for l in lights {
            for &b in &boxes {
                casters(b, l, bounded, bvh, &mut found);
                let all = chunks.len() as u32;
                push_chunks(&mut chunks, found.iter().copied());
                let others = chunks.len() as u32;
                push_chunks(&mut chunks, found.iter().copied().filter(|&(i, _)| i != me));
                ranges.push([all, others, chunks.len() as u32]);
            }
        }
        Some(Self {
            a,
            u,
            len,
            pieces,
            lights: lights.len(),
            chunks,
            ranges,
        })
    }

    /// These casters of object `me` with `shape` for `lights`, found when the
    /// objects flagged in `moved` were elsewhere (`me` not among them), now
    /// that those objects have moved from and to the boxes `boxes` and lie
    /// in the boxes `now` (object and box, in query order).
    ///
    /// Where none of the object's reaches meets one of `boxes`, no list can
    /// have gained or lost one of those objects: they are kept as they are.
    /// Otherwise each list keeps its objects that did not move, in their
    /// order, and gains after them the moved ones whose box meets its reach
    /// now (a list no moved object enters or leaves is copied whole): the
    /// objects a fresh list holds, with the same boxes, the moved ones last. A
    /// shadow test's yes or no does not depend on the order; which blocker it
    /// names first may.
    pub(crate) fn updated(
        self,
        (me, shape): (usize, &Shape),
        lights: &[Light],
        (boxes, moved, now): (&[Aabb], &[bool], &[(usize, Aabb)]),
    ) -> Self {
        let reaches = Reaches::of(shape, lights);
        if reaches.miss(boxes) {
            return self;
        }
        self.patched(me, &reaches, moved, now)
    }

    /// Whether [`Self::updated`] keeps the casters of an object with `shape`
    /// for `lights` as they are, the moved objects' boxes (where they were
    /// and where they are) being `moved`.
    #[cfg(test)]
    pub(crate) fn keep_for(shape: &Shape, lights: &[Light], moved: &[Aabb]) -> bool {
        Reaches::of(shape, lights).miss(moved)
    }

    /// [`Self::updated`] where a moved box meets a reach: the lists patched.
    fn patched(&self, me: usize, reaches: &Reaches, moved: &[bool], now: &[(usize, Aabb)]) -> Self {
        let mut chunks = Vec::with_capacity(self.chunks.len());
        let mut ranges = Vec::with_capacity(self.ranges.len());
        let (mut list, mut near) = (Vec::new(), Vec::new());
        for (li, (per_piece, all)) in reaches.0.iter().enumerate() {
            near.clear();
            near.extend(now.iter().filter(|(_, b)| b.overlaps(all)));
            for (piece, reach) in per_piece.iter().enumerate() {
                let [from, to, end] = self.ranges[li * self.pieces + piece].map(|i| i as usize);
                let old = WideList::of(&self.chunks, from..to);
                let gains = |r: &&Reach| near.iter().any(|(_, b)| r.meets(b));
                if reach.as_ref().is_none_or(|r| !gains(&r)) && !old.items().any(|i| moved[i]) {
                    // No moved object enters or leaves: both lists as they were.
                    let at = chunks.len() as u32;
                    chunks.extend_from_slice(&self.chunks[from..end]);
                    let shift = |i: usize| at + (i - from) as u32;
                    ranges.push([at, shift(to), shift(end)]);
                    continue;
                }
                list.clear();
                if let Some(reach) = reach {
                    list.extend(old.entries().filter(|&(i, _)| !moved[i]));
                    list.extend(near.iter().filter(|(_, b)| reach.meets(b)));
                }
                let all = chunks.len() as u32;
                push_chunks(&mut chunks, list.iter().copied());
                let others = chunks.len() as u32;
                push_chunks(&mut chunks, list.iter().copied().filter(|&(i, _)| i != me));
                ranges.push([all, others, chunks.len() as u32]);
            }
        }
        Self {
            chunks,
            ranges,
            ..*self
        }
    }

    /// The casters towards light `light` of a shadow ray starting at `at`, from
    /// a point met from `outside` (then without the object itself).
    pub(crate) fn at(&self, light: usize, at: Vec3, outside: bool) -> Option<WideList<'_>> {
        self.list(light, self.piece(at), outside)
    }

    /// The piece a shadow ray starting at `at` starts from.
    #[inline]
    pub(crate) fn piece(&self, at: Vec3) -> usize {
        if self.pieces == 1 {
            0
        } else {
            let s = (at - self.a).dot(self.u) / self.len * self.pieces as f32;
            // Clamped to the ends (the caps' starts lie just beyond them); NaN to 0.
            (s.max(0.0) as usize).min(self.pieces - 1)
        }
    }

    /// What [`Self::piece`] computes with: the axis' start, unit axis and
    /// length, and the pieces.
    pub(crate) fn axis(&self) -> (Vec3, Vec3, f32, usize) {
        (self.a, self.u, self.len, self.pieces)
    }

    /// The casters towards light `light` of piece `piece`, with the object
    /// itself or (`outside`) without.
    #[inline]
    pub(crate) fn list(&self, light: usize, piece: usize, outside: bool) -> Option<WideList<'_>> {
        if light >= self.lights {
            return None;
        }
        let r = self.ranges[light * self.pieces + piece];
        let (from, to) = if outside { (r[1], r[2]) } else { (r[0], r[1]) };
        Some(WideList::of(&self.chunks, from as usize..to as usize))
    }
}

/// How far outside (m) [`clear_of`] asks a point to be.
pub(crate) const MARGIN: f32 = 1e-5;

/// Whether `p` lies clearly outside the shape `g` (by more than 1e-5 m, half the
/// offset secondary rays start at): only then does a shadow ray from a point met
/// from outside skip the object itself. A start inside it (a ray that began in a
/// touching neighbour met it from within, by rounding, as "outside") tests it, as
/// the reference does.
pub(crate) fn clear_of(g: &Geom, p: Vec3) -> bool {
    match *g {
        Geom::Sphere { centre, radius } => {
            (p - centre).length_squared() > (radius + MARGIN) * (radius + MARGIN)
        }
        Geom::Cylinder(ref c) => c.clear_of(p, MARGIN),
        Geom::Plane { .. } => true,
    }
}

#[cfg(test)]
mod tests {
    use super::{Casters, Reach, Reaches, piece_boxes};
    use crate::geometry::{Aabb, bounds};
    use crate::scene::{Light, Shape};
    use glam::Vec3;

    /// Whether a moved box meets one of the reaches of `shape`'s pieces
    /// towards `lights`, each piece against each box: what
    /// [`Casters::keep_for`] answers, worked out without its first test.
    fn kept_piece_by_piece(shape: &Shape, lights: &[Light], moved: &[Aabb]) -> bool {
        lights.iter().all(|l| {
            piece_boxes(shape)
                .into_iter()
                .all(|b| Reach::new(b, l).is_none_or(|reach| !moved.iter().any(|m| reach.meets(m))))
        })
    }

    /// A ball of radius 2 cm at `centre`, on two strings from the rail at
    /// `x`, 0.2 m up and 8 cm either side, pushed onto `shapes`.
    fn pendulum(shapes: &mut Vec<Shape>, x: f32, centre: Vec3) {
        shapes.push(Shape::Sphere {
            centre,
            radius: 0.02,
        });
        for z in [-0.08, 0.08] {
            shapes.push(Shape::Cylinder {
                a: Vec3::new(x, 0.2, z),
                b: centre,
                radius: 0.0005,
            });
        }
    }

    /// A white point light at `position`.
    fn point(position: Vec3) -> Light {
        Light::Point {
            position,
            color: Vec3::ONE,
        }
    }

    /// A white directional light along `direction` (normalized here).
    fn directional(direction: Vec3) -> Light {
        Light::Directional {
            direction: direction.normalize(),
            color: Vec3::ONE,
        }
    }

    /// A list's place (light, piece, outside) and its objects with their
    /// boxes, in order.
    type List = ((usize, usize, bool), Vec<(usize, Aabb)>);

    /// Each list of `c`.
    fn lists(c: &Casters, lights: usize) -> Vec<List> {
        let mut out = Vec::new();
        for l in 0..lights {
            for piece in 0..c.pieces {
                for outside in [false, true] {
                    let list = c.list(l, piece, outside).expect("a light");
                    out.push(((l, piece, outside), list.entries().collect()));
                }
            }
        }
        out
    }

    #[test]
    fn patched_casters_hold_what_fresh_ones_hold_with_the_moved_objects_last() {
        let lights = [
            point(Vec3::new(0.3, 0.6, 0.5)),
            directional(Vec3::new(-0.4, -1.0, 0.1)),
            Light::Ambient { color: Vec3::ONE },
        ];
        // Five balls touching in a row, each on two slanted strings.
        let row = |swing: f32| {
            let mut shapes = Vec::new();
            for k in 0..5 {
                let x = -0.08 + 0.04 * k as f32;
                // The first pendulum swung out by `swing` radians.
                let a = if k == 0 { swing } else { 0.0 };
                let centre = Vec3::new(x - 0.16 * a.sin(), 0.2 - 0.16 * a.cos(), 0.0);
                pendulum(&mut shapes, x, centre);
            }
            shapes
        };
        let bounded = |shapes: &[Shape]| -> Vec<(usize, Aabb)> {
            (shapes.iter().enumerate())
                .map(|(i, s)| (i, bounds(s).expect("a box")))
                .collect()
        };
        let fresh = |shapes: &[Shape]| -> Vec<Casters> {
            let b = bounded(shapes);
            (shapes.iter().enumerate())
                .map(|(i, s)| Casters::new((i, s), &lights, &b, None).expect("bounded"))
                .collect()
        };
        // Swung out, then back through the row's place (where it blocks its
        // neighbour's rays), then out again.
        let mut changed = 0;
        for (from, to) in [(0.0, 0.5), (0.5, 0.0), (0.5, 0.4), (0.0, -0.3)] {
            let (before, after) = (row(from), row(to));
            let moved: Vec<bool> = (0..before.len()).map(|i| i < 3).collect();
            let now: Vec<(usize, Aabb)> = (bounded(&after).into_iter())
                .filter(|&(i, _)| moved[i])
                .collect();
            let (old, new) = (fresh(&before), fresh(&after));
            for i in 3..before.len() {
                let reaches = Reaches::of(&after[i], &lights);
                let patched = old[i].patched(i, &reaches, &moved, &now);
                let (got, want) = (lists(&patched, 2), lists(&new[i], 2));
                if lists(&old[i], 2) != want {
                    changed += 1;
                }
                for ((at, mut got), (_, mut want)) in got.into_iter().zip(want) {
                    // The moved objects come after the others.
                    let first = got.iter().position(|&(k, _)| moved[k]);
                    if let Some(f) = first {
                        assert!(got[f..].iter().all(|&(k, _)| moved[k]), "{i} {at:?}");
                    }
                    let key = |e: &(usize, Aabb)| e.0;
                    got.sort_by_key(key);
                    want.sort_by_key(key);
                    assert_eq!(got, want, "object {i}, {at:?}, {from} -> {to}");
                }
            }
        }
        // Some lists did change: the moved pendulum enters and leaves them.
        assert!(changed > 0);
    }

    #[test]
    fn keeping_casters_answers_as_the_test_of_every_piece_against_every_moved_box() {
        // Point lights above the row and beside it, a light straight down
        // (its direction has zero components: the reaches' slabs along those
        // axes are unbounded) and a slanted one.
        let lights = [
            point(Vec3::new(0.7, 0.6, 0.5)),
            point(Vec3::new(-2.5, 0.1, -0.3)),
            directional(Vec3::NEG_Y),
            directional(Vec3::new(0.3, -1.0, 0.2)),
            Light::Ambient { color: Vec3::ONE },
        ];
        // A row of balls, each on two slanted strings.
        let mut shapes = Vec::new();
        for k in 0..12 {
            let x = -2.0 + 0.1 * k as f32;
            pendulum(&mut shapes, x, Vec3::new(x, 0.05, 0.0));
        }
        let (mut kept, mut not) = (0, 0);
        // A small moved box at each point of a grid over the row and above
        // it (1.3 cm apart across, so that some lie within a reach's
        // widening of its segment and some just beyond), and the row's
        // first three balls moved together.
        let small = |c: Vec3| {
            bounds(&Shape::Sphere {
                centre: c,
                radius: 0.002,
            })
            .expect("a box")
        };
        let mut sets: Vec<Vec<Aabb>> = Vec::new();
        for i in 0..100 {
            for j in 0..5 {
                for z in [-0.05, 0.0, 0.05] {
                    let x = -2.2 + 0.013 * i as f32;
                    sets.push(vec![small(Vec3::new(x, 0.08 * j as f32, z))]);
                }
            }
        }
        sets.push(
            (0..3)
                .flat_map(|j| {
                    let c = Vec3::new(-2.0 + 0.1 * j as f32, 0.05, 0.0);
                    [c, c + Vec3::new(0.03, 0.01, 0.0)]
                })
                .map(|centre| {
                    bounds(&Shape::Sphere {
                        centre,
                        radius: 0.02,
                    })
                    .expect("a box")
                })
                .collect(),
        );
        for moved in &sets {
            for shape in &shapes {
                for ls in [&lights[..], &lights[0..1], &lights[2..3], &lights[3..4]] {
                    let want = kept_piece_by_piece(shape, ls, moved);
                    assert_eq!(Casters::keep_for(shape, ls, moved), want, "{shape:?}");
                    if want {
                        kept += 1;
                    } else {
                        not += 1;
                    }
                }
            }
        }
        // Both answers come up often.
        assert!(kept > 1_000 && not > 100, "kept {kept}, not {not}");
    }
}
