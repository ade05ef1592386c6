//! The motion filter's screen half: where on the picture a moved shape can
//! change a pixel through the pixel's free segments (`Motion::free`), which
//! leave no cells. A camera ray comes near a shape only where the shape shows
//! on the screen; the mirror ray of a camera ray off a plane only where the
//! shape's mirror image in the plane shows; and a shadow ray from where a
//! camera ray met a plane only where the shape's shadow on the plane shows.
//! Each of those regions is bounded by the images of the corners of a box
//! around the shape (mirrored or cast onto the plane, then seen): for a ball
//! their screen box, met with the ball's exact one and, row by row, with its
//! ellipse (`conic`); for a string a rectangle along the image of its axis. Padded, per row, [`Spans`] holds their union
//! as runs of pixels. `Moved::dirty` takes a pixel in a run as a candidate
//! whatever its cells.

use crate::camera::CameraRays;
use crate::geometry::Aabb;
use crate::scene::{Light, Scene, Shape};
use glam::Vec3;

mod ball;
mod conic;
use ball::ball_box;
use conic::Conic;

/// Pixels added on each side of a region's screen box. Pixel `k` holds samples
/// at `k + [0, 1)`, so the pixels whose samples can fall within `x0..=x1` are
/// `floor(x0)..=floor(x1)`: what flooring `x0` and ceiling `x1` give with any
/// pad above nought (the same for rows, and for a quad's band of rows). The pad
/// covers the rounding of the f32 projection (about 1e-3 pixel at a thousand
/// pixels); what the tracer's rounding moves in the scene (its hit points, the
/// shadow and mirror rays starting `SURFACE_OFFSET` = 2e-5 m off the plane) is
/// held by the pieces' growth of twice `Near::PAD` (2e-4 m). At 2.0 the runs of
/// the default swing held 16% more pixels.
const PAD_PX: f32 = 0.5;

/// Per row, the runs of pixels `x0..x1` (ascending, apart) where a moved shape
/// may show on the screen, in the plane's mirror or as a shadow on a plane.
#[derive(Debug, Clone, Default)]
pub(crate) struct Spans {
    runs: Vec<(u32, u32)>,
    /// Row `y`'s runs: `runs[start[y]..start[y + 1]]`.
    start: Vec<u32>,
}

impl Spans {
    /// The runs of the shapes within `pieces` seen by `cam` in `scene`
    /// (`None`: a shape without a box, so every pixel).
    pub(crate) fn new(cam: &CameraRays, scene: &Scene, pieces: Option<&[Piece]>) -> Self {
        let (w, h) = scene.size;
        let mut cover: Vec<(u32, u32, u32)> = Vec::new();
        let whole = [[0.0, w as f32], [0.0, h as f32]];
        // Clamped to the picture (NaN to 0: `as` saturates).
        let px = |v: f32, n: u32| (v.max(0.0) as u32).min(n);
        let mut add = |r: Option<Region>| match r.unwrap_or(Region::Box(whole)) {
            Region::Box([[x0, x1], [y0, y1]]) => {
                let (x0, x1) = (px((x0 - PAD_PX).floor(), w), px((x1 + PAD_PX).ceil(), w));
                let (y0, y1) = (px((y0 - PAD_PX).floor(), h), px((y1 + PAD_PX).ceil(), h));
                if x0 < x1 {
                    cover.extend((y0..y1).map(|y| (y, x0, x1)));
                }
            }
            Region::Ellipse(conic, [[x0, x1], [y0, y1]]) => {
                // Per row, the ellipse's span in the row's band, within the box.
                for y in px((y0 - PAD_PX).floor(), h)..px((y1 + PAD_PX).ceil(), h) {
                    let band = (y as f32 - PAD_PX, y as f32 + 1.0 + PAD_PX);
                    if let Some((l, r)) = conic.band_x(band) {
                        let (l, r) = (l.max(x0) - PAD_PX, r.min(x1) + PAD_PX);
                        let (l, r) = (px(l.floor(), w), px(r.ceil(), w));
                        if l < r {
                            cover.push((y, l, r));
                        }
                    }
                }
            }
            Region::Quad(q) => {
                // Padded already; per row, where the quad crosses the row's band.
                let (y0, y1) = q
                    .iter()
                    .fold((f32::MAX, f32::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
                for y in px(y0.floor(), h)..px(y1.ceil(), h) {
                    if let Some((x0, x1)) = band_x(&q, (y as f32, y as f32 + 1.0)) {
                        let (x0, x1) = (px(x0.floor(), w), px(x1.ceil(), w));
                        if x0 < x1 {
                            cover.push((y, x0, x1));
                        }
                    }
                }
            }
        };
        match pieces {
            None => add(None),
            Some(pieces) => {
                let maps = maps(scene);
                for piece in pieces {
                    for m in &maps {
                        add(piece.region(cam, m));
                    }
                }
            }
        }
        cover.sort_unstable();
        let mut runs: Vec<(u32, u32)> = Vec::with_capacity(cover.len());
        let mut start = vec![0u32; h as usize + 1];
        let mut last_y = u32::MAX;
        for (y, x0, x1) in cover {
            match runs.last_mut() {
                Some(run) if y == last_y && x0 <= run.1 => run.1 = run.1.max(x1),
                _ => runs.push((x0, x1)),
            }
            last_y = y;
            start[y as usize + 1] = runs.len() as u32;
        }
        // Rows without runs start where the row before ends.
        for y in 1..start.len() {
            start[y] = start[y].max(start[y - 1]);
        }
        Self { runs, start }
    }

    /// Row `y`'s runs (none past the picture).
    pub(crate) fn row(&self, y: usize) -> &[(u32, u32)] {
        match (self.start.get(y), self.start.get(y + 1)) {
            (Some(&a), Some(&b)) => &self.runs[a as usize..b as usize],
            _ => &[],
        }
    }
}

/// A part of a moved shape, grown as [`crate::motion::Near`] grows it (and
/// more): a piece of a string or rod (its axis from one point to another and
/// its grown radius), or a ball, whose screen box is worked out exactly as well
/// ([`ball_box`]).
#[derive(Debug, Clone, Copy)]
pub(crate) enum Piece {
    Rod(Vec3, Vec3, f32),
    Ball(Vec3, f32),
}

/// Where a piece may show on the screen, in pixels: a box `[[x0, x1], [y0,
/// y1]]` (padded when added), a ball's ellipse within such a box, or a convex
/// quad, padded.
#[derive(Debug, Clone, Copy)]
enum Region {
    Box([[f32; 2]; 2]),
    /// A ball's ellipse, within its box.
    Ellipse(Conic, [[f32; 2]; 2]),
    Quad([(f32, f32); 4]),
}

impl Piece {
    /// Its region under `m` (`None`: every pixel).
    fn region(&self, cam: &CameraRays, m: &Map) -> Option<Region> {
        match *self {
            Piece::Rod(a, b, g) => rod_region(cam, (a, b, g), m),
            Piece::Ball(c, r) => {
                let b = Aabb {
                    min: c - Vec3::splat(r),
                    max: c + Vec3::splat(r),
                };
                // Both bound the image: the corners' box says it is in front and
                // bounded, the exact one is tighter.
                let [bx, by] = screen_box(cam, &b, m)?;
                let Some([ex, ey]) = ball_box(cam, (c, r), m) else {
                    return Some(Region::Box([bx, by]));
                };
                let meet = |a: [f32; 2], e: [f32; 2]| [a[0].max(e[0]), a[1].min(e[1])];
                let boxed = [meet(bx, ex), meet(by, ey)];
                Some(match Conic::of_ball(cam, (c, r), m) {
                    Some(conic) => Region::Ellipse(conic, boxed),
                    None => Region::Box(boxed),
                })
            }
        }
    }
}

/// How a point of a shape maps to a point whose screen position bounds where it
/// shows: itself (camera rays), its mirror image in a plane (a plane's mirror
/// rays), its shadow on a plane from a light (a plane's shadow rays).
#[derive(Debug, Clone, Copy)]
enum Map {
    Eye,
    Mirror {
        point: Vec3,
        normal: Vec3,
    },
    /// From point light `from` onto the plane.
    Cast {
        point: Vec3,
        normal: Vec3,
        from: Vec3,
    },
    /// Along `along` (a directional light's travel) onto the plane.
    Along {
        point: Vec3,
        normal: Vec3,
        along: Vec3,
    },
}

/// The maps of `scene`: the eye's, and per plane its mirror and a cast per
/// light that throws shadows.
fn maps(scene: &Scene) -> Vec<Map> {
    let mut out = vec![Map::Eye];
    for o in &scene.objects {
        let Shape::Plane { point, normal } = o.shape else {
            continue;
        };
        let normal = normal.normalize();
        out.push(Map::Mirror { point, normal });
        for l in &scene.lights {
            match *l {
                Light::Ambient { .. } => {}
                Light::Point { position, .. } => out.push(Map::Cast {
                    point,
                    normal,
                    from: position,
                }),
                Light::Directional { direction, .. } => out.push(Map::Along {
                    point,
                    normal,
                    along: direction,
                }),
            }
        }
    }
    out
}

/// Where `x` goes under `m`; `None` where the image is unbounded (a point
/// level with or above the light, a light along the plane).
fn apply(m: &Map, x: Vec3) -> Option<Vec3> {
    match *m {
        Map::Eye => Some(x),
        Map::Mirror { point, normal } => Some(x - 2.0 * (x - point).dot(normal) * normal),
        Map::Cast {
            point,
            normal,
            from,
        } => {
            // Heights over the plane on the light's side.
            let hl = (from - point).dot(normal);
            let n = if hl < 0.0 { -normal } else { normal };
            let (hl, hx) = (hl.abs(), (x - point).dot(n));
            // The line from the light through x meets the plane beyond x only
            // where x is below the light; near level, its image runs off.
            (hx < hl * 0.999 && hl > 1e-6).then(|| from + (x - from) * (hl / (hl - hx)))
        }
        Map::Along {
            point,
            normal,
            along,
        } => {
            let across = along.dot(normal);
            (across.abs() > 1e-3).then(|| x - along * ((x - point).dot(normal) / across))
        }
    }
}

/// The screen box, `[[x0, x1], [y0, y1]]` in pixels, of the images under `m`
/// of the corners of `b`, which bounds the image of the box (all of the maps
/// keep straight lines straight, so the image of the box is the hull of its
/// corners'); `None` (every pixel) where one is unbounded, behind the eye or
/// not finite.
fn screen_box(cam: &CameraRays, b: &Aabb, m: &Map) -> Option<[[f32; 2]; 2]> {
    let mut r = [[f32::INFINITY, f32::NEG_INFINITY]; 2];
    for i in 0..8 {
        let corner = Vec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        );
        let (x, y) = cam.project(apply(m, corner)?)?;
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        r[0] = [r[0][0].min(x), r[0][1].max(x)];
        r[1] = [r[1][0].min(y), r[1][1].max(y)];
    }
    Some(r)
}

/// The region of the rod from `a` to `b` of radius `g` under `m`: the box
/// around it (along its axis, and `g` either side across, which holds the
/// capsule) has 8 corners whose images bound its image; on the screen they
/// lie in a rectangle along the image of the axis (a straight line: every map
/// keeps lines straight), padded by [`PAD_PX`]. `None` where a corner's image
/// is unbounded or behind the eye.
fn rod_region(cam: &CameraRays, (a, b, g): (Vec3, Vec3, f32), m: &Map) -> Option<Region> {
    // (A piece of no length: any axis; the box then holds the ball around it.)
    let w = (b - a).try_normalize().unwrap_or(Vec3::X);
    let (e1, e2) = w.any_orthonormal_pair();
    let (a, b) = (a - w * g, b + w * g);
    let mut q = [(0.0f32, 0.0f32); 8];
    for (i, q) in q.iter_mut().enumerate() {
        let end = if i & 1 == 0 { a } else { b };
        let s1 = if i & 2 == 0 { -g } else { g };
        let s2 = if i & 4 == 0 { -g } else { g };
        *q = cam.project(apply(m, end + e1 * s1 + e2 * s2)?)?;
        if !(q.0.is_finite() && q.1.is_finite()) {
            return None;
        }
    }
    // The axis on the screen: through the images of its ends.
    let (o, e) = (cam.project(apply(m, a)?)?, cam.project(apply(m, b)?)?);
    let (dx, dy) = (e.0 - o.0, e.1 - o.1);
    let len = (dx * dx + dy * dy).sqrt();
    if len.is_nan() || len <= 1e-3 {
        let (lo, hi) = q
            .iter()
            .fold(((f32::MAX, f32::MAX), (f32::MIN, f32::MIN)), |(l, h), p| {
                ((l.0.min(p.0), l.1.min(p.1)), (h.0.max(p.0), h.1.max(p.1)))
            });
        return Some(Region::Box([[lo.0, hi.0], [lo.1, hi.1]]));
    }
    let (u, v) = ((dx / len, dy / len), (-dy / len, dx / len));
    let at = |p: &(f32, f32), d: (f32, f32)| (p.0 - o.0) * d.0 + (p.1 - o.1) * d.1;
    let span = |d| {
        q.iter().fold((f32::MAX, f32::MIN), |(l, h), p| {
            (l.min(at(p, d)), h.max(at(p, d)))
        })
    };
    let ((t0, t1), (s0, s1)) = (span(u), span(v));
    let (t0, t1, s0, s1) = (t0 - PAD_PX, t1 + PAD_PX, s0 - PAD_PX, s1 + PAD_PX);
    let corner = |t: f32, s: f32| (o.0 + u.0 * t + v.0 * s, o.1 + u.1 * t + v.1 * s);
    Some(Region::Quad([
        corner(t0, s0),
        corner(t1, s0),
        corner(t1, s1),
        corner(t0, s1),
    ]))
}

/// The least and greatest x of the convex quad `q` within the band of rows
/// from `y0` to `y1`: among its corners in the band and where its sides cross
/// the band's edges. `None` where it misses the band.
fn band_x(q: &[(f32, f32); 4], (y0, y1): (f32, f32)) -> Option<(f32, f32)> {
    let (mut lo, mut hi) = (f32::MAX, f32::MIN);
    for i in 0..4 {
        let (p, r) = (q[i], q[(i + 1) % 4]);
        if (y0..=y1).contains(&p.1) {
            (lo, hi) = (lo.min(p.0), hi.max(p.0));
        }
        for y in [y0, y1] {
            if (p.1 - y) * (r.1 - y) < 0.0 {
                let x = p.0 + (r.0 - p.0) * ((y - p.1) / (r.1 - p.1));
                (lo, hi) = (lo.min(x), hi.max(x));
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

#[cfg(test)]
#[path = "screen_tests.rs"]
mod tests;
