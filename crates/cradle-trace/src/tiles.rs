//! Screen tiles for primary rays: each tile lists only the objects whose projected
//! bounds can cover it. A primary ray through the tile can hit nothing else, so
//! testing the list gives the same nearest hit as testing everything (the lists keep
//! the query order, so ties resolve the same way too).

use super::camera::CameraRays;
use super::geometry::Aabb;
use super::prepared::Prepared;
use super::scene::Shape;
pub use super::tuning::TILE;
use glam::Vec3;

/// Primary-ray candidates per tile, and for each plane the candidates of the
/// rays it reflects.
#[derive(Debug, Clone)]
pub struct Tiles {
    across: u32,
    lists: Lists,
    /// Per object, its pixel rectangle with margin, for finer lists per packet.
    rects: Vec<[f32; 4]>,
    /// Per plane (object index), lists for its mirror rays.
    mirrors: Vec<(usize, Lists)>,
}

/// The bounded candidates whose rectangles reach a packet's pixels.
#[derive(Debug, Clone, Copy, Default)]
pub struct Reaching {
    ids: [usize; Self::MAX],
    len: usize,
}

impl Reaching {
    /// At most this many; a packet reached by more is traced pixel by pixel.
    pub const MAX: usize = super::tuning::TILE_LIST_AT_MOST;

    /// The object indices, in query order.
    #[must_use]
    pub fn as_slice(&self) -> &[usize] {
        &self.ids[..self.len]
    }
}

/// The box holding `b` mirrored in the plane through `point` with unit `normal`.
fn mirrored(b: Aabb, point: Vec3, normal: Vec3) -> Aabb {
    b.corners().into_iter().fold(Aabb::EMPTY, |m, c| {
        let r = c - 2.0 * (c - point).dot(normal) * normal;
        m.union(Aabb { min: r, max: r })
    })
}

impl Tiles {
    /// Candidate lists for a `width` x `height` picture: for primary rays, and for
    /// the rays each plane reflects.
    ///
    /// A plane is a mirror: the ray it reflects at `P` is the primary ray's
    /// continuation beyond `P` mirrored in it, so it meets an object exactly where
    /// the continuation meets the object's mirror image, which the eye sees through
    /// the same pixel. So the mirror rays of a pixel can only hit the objects whose
    /// mirrored boxes cover its tile. The reflected ray's start (lifted off the
    /// surface by 2e-5 m) and rounding move it by far less than the one pixel of
    /// margin.
    #[must_use]
    pub fn new(p: &Prepared<'_>, cam: &CameraRays, width: u32, height: u32) -> Self {
        let objects = p.in_query_order().collect::<Vec<_>>();
        // Each plane (object index, point, normal), for its mirror and shadow lists.
        let planes = || {
            p.scene
                .objects
                .iter()
                .enumerate()
                .filter_map(|(i, o)| match o.shape {
                    Shape::Plane { point, normal } => Some((i, point, normal)),
                    _ => None,
                })
        };
        // The two parts on two threads where the pool has them: the mirror
        // lists on one, the primary lists on the other.
        let (mirrors, (lists, rects)) = rayon::join(
            || {
                planes()
                    .map(|(i, point, normal)| {
                        let image = objects
                            .iter()
                            .map(|&(k, b)| (k, b.map(|b| mirrored(b, point, normal))));
                        (i, lists(image, cam, width, height))
                    })
                    .collect()
            },
            || lists_and_rects(objects.iter().copied(), cam, width, height),
        );
        Self {
            across: width.div_ceil(TILE),
            lists,
            rects,
            mirrors,
        }
    }

    /// The one plane among the candidates whose rectangles reach pixels `x..x +
    /// n` of row `y` (all in one tile); the other such candidates (at most
    /// [`Reaching::MAX`], in query order) go to `others` (filled in place: no
    /// copy of the list). `None` for no plane, several, or too many others. A
    /// primary ray through those pixels can hit nothing else.
    #[must_use]
    #[inline]
    pub fn plane_among(
        &self,
        p: &Prepared<'_>,
        (x, y, n): (u32, u32, u32),
        others: &mut Reaching,
    ) -> Option<usize> {
        // Planes reach every tile and come first in query order, so a tile's
        // list starts with all of them: one plane, or the scalar path.
        let ([plane], Some((&first, rest))) = (p.planes(), self.at(x, y).split_first()) else {
            return None;
        };
        if first != *plane {
            return None;
        }
        let (xa, xb, ya, yb) = (x as f32, (x + n) as f32, y as f32, (y + 1) as f32);
        others.len = 0;
        for &i in rest {
            let [x0, y0, x1, y1] = self.rects[i];
            if x1 < xa || x0 > xb || y1 < ya || y0 > yb {
                continue;
            }
            if others.len == Reaching::MAX {
                return None;
            }
            others.ids[others.len] = i;
            others.len += 1;
        }
        Some(first)
    }

    /// The candidates of pixel `(x, y)`.
    #[must_use]
    pub fn at(&self, x: u32, y: u32) -> &[usize] {
        self.lists.of(self.tile(x, y))
    }

    /// The candidates of the rays that plane `plane` reflects at pixel `(x, y)`
    /// (`None` when `plane` is not a plane).
    #[must_use]
    pub fn mirror_at(&self, plane: usize, x: u32, y: u32) -> Option<&[usize]> {
        let tile = self.tile(x, y);
        self.mirrors
            .iter()
            .find(|(i, _)| *i == plane)
            .map(|(_, lists)| lists.of(tile))
    }

    fn tile(&self, x: u32, y: u32) -> usize {
        ((y / TILE) * self.across + x / TILE) as usize
    }
}

/// Each tile's list of objects, in one vector: tile `t`'s are
/// `ids[start[t]..start[t + 1]]` (two allocations for all, not one a tile).
#[derive(Debug, Clone)]
struct Lists {
    start: Vec<u32>,
    ids: Vec<usize>,
}

impl Lists {
    /// Tile `t`'s objects.
    fn of(&self, t: usize) -> &[usize] {
        &self.ids[self.start[t] as usize..self.start[t + 1] as usize]
    }
}

/// Per tile, the objects (index, bounds in query order; `None` for planes) whose
/// screen bounds cover it.
fn lists(
    objects: impl Iterator<Item = (usize, Option<Aabb>)>,
    cam: &CameraRays,
    width: u32,
    height: u32,
) -> Lists {
    lists_and_rects(objects, cam, width, height).0
}

/// [`lists`], and each object's pixel rectangle `[x0, y0, x1, y1]` with its margin
/// (infinite for planes, open to each side where a box reaches behind the
/// eye), by object index.
fn lists_and_rects(
    objects: impl Iterator<Item = (usize, Option<Aabb>)>,
    cam: &CameraRays,
    width: u32,
    height: u32,
) -> (Lists, Vec<[f32; 4]>) {
    let across = width.div_ceil(TILE);
    let down = height.div_ceil(TILE);
    let tiles = (across * down) as usize;
    // Each object's tiles, columns and rows (inclusive), in query order.
    let mut spans = Vec::new();
    let mut rects = Vec::new();
    for (i, bounds) in objects {
        // Planes (no bounds) go everywhere; a box where its image in front
        // of the eye shows (open to each side where it reaches behind,
        // `CameraRays::hull_box`).
        let (x0, y0, x1, y1) = match bounds.map(|b| cam.hull_box(&b.corners())) {
            // One pixel of margin covers round-off in the projection and the
            // sub-pixel sample offsets.
            Some([[a, c], [b, d]]) => (a - 1.0, b - 1.0, c + 1.0, d + 1.0),
            None => (
                f32::NEG_INFINITY,
                f32::NEG_INFINITY,
                f32::INFINITY,
                f32::INFINITY,
            ),
        };
        if rects.len() <= i {
            rects.resize(i + 1, [0.0; 4]);
        }
        rects[i] = [x0, y0, x1, y1];
        if x1 < 0.0 || y1 < 0.0 || x0 > width as f32 || y0 > height as f32 {
            continue;
        }
        let tx = |x: f32| ((x.max(0.0) / TILE as f32) as u32).min(across - 1);
        let ty = |y: f32| ((y.max(0.0) / TILE as f32) as u32).min(down - 1);
        spans.push((i, [tx(x0), tx(x1)], [ty(y0), ty(y1)]));
    }
    // Count each tile's objects, then place them: the lists in query order.
    let mut start = vec![0u32; tiles + 1];
    let each = |f: &mut dyn FnMut(usize, usize)| {
        for &(i, [c0, c1], [r0, r1]) in &spans {
            for row in r0..=r1 {
                for col in c0..=c1 {
                    f((row * across + col) as usize, i);
                }
            }
        }
    };
    each(&mut |t, _| start[t + 1] += 1);
    for t in 0..tiles {
        start[t + 1] += start[t];
    }
    let mut ids = vec![0; start[tiles] as usize];
    let mut next = start.clone();
    each(&mut |t, i| {
        ids[next[t] as usize] = i;
        next[t] += 1;
    });
    (Lists { start, ids }, rects)
}
