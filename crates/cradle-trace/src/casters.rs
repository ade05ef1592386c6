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
        Some(Self {
            centre,
            inv: dir.recip(),
            widen: 0.5 * (from.max - from.min).length() + 1e-4 + 1e-4 * scale,
            t_max,
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
        let mut chunks = Vec::new();
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

    /// Whether the casters of an object with `shape` for `lights` are what
    /// they were when only objects whose boxes (where they were and where
    /// they are) are `moved` have moved since, the object not among them:
    /// none of its lists can hold one of those boxes, so each holds the same
    /// objects, with the same boxes.
    pub(crate) fn keep_for(shape: &Shape, lights: &[Light], moved: &[Aabb]) -> bool {
        let boxes = piece_boxes(shape);
        lights.iter().all(|l| {
            boxes.iter().all(|&b| {
                Reach::new(b, l).is_none_or(|reach| !moved.iter().any(|m| reach.meets(m)))
            })
        })
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
