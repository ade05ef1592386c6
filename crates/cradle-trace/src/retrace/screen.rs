//! The motion filter's screen half: where on the picture a moved shape can
//! change a pixel through the pixel's free segments (`Motion::free`), which
//! leave no cells. A camera ray comes near a shape only where the shape shows
//! on the screen; the mirror ray of a camera ray off a plane only where the
//! shape's mirror image in the plane shows; and a shadow ray from where a
//! camera ray met a plane only where the shape's shadow on the plane shows.
//! Each of those regions is bounded by the screen box of a few points (the
//! corners of the shape's boxes, mirrored or cast onto the plane), padded; per
//! row, [`Spans`] holds their union as runs of pixels. `Moved::dirty` takes a
//! pixel in a run as a candidate whatever its cells.

use crate::camera::CameraRays;
use crate::geometry::Aabb;
use crate::scene::{Light, Scene, Shape};
use glam::{DVec3, Vec3};

/// Pixels added on each side of a region's screen box: 1 because a pixel's
/// samples lie anywhere in it, 1 more for every rounding on the way (the f32
/// projection, the tracer's hit points, the shadow and mirror rays starting
/// `SURFACE_OFFSET` = 2e-5 m off the plane: each well under 0.1 pixel at the
/// scene's scale, where a pixel spans about a millimetre).
const PAD_PX: f32 = 2.0;

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
        let mut add = |r: Option<[[f32; 2]; 2]>| {
            let [[x0, x1], [y0, y1]] = r.unwrap_or(whole);
            // Clamped to the picture (NaN to 0: `as` saturates).
            let px = |v: f32, n: u32| (v.max(0.0) as u32).min(n);
            let (x0, x1) = (px((x0 - PAD_PX).floor(), w), px((x1 + PAD_PX).ceil(), w));
            let (y0, y1) = (px((y0 - PAD_PX).floor(), h), px((y1 + PAD_PX).ceil(), h));
            if x0 < x1 {
                cover.extend((y0..y1).map(|y| (y, x0, x1)));
            }
        };
        match pieces {
            None => add(None),
            Some(pieces) => {
                let maps = maps(scene);
                for piece in pieces {
                    for m in &maps {
                        add(piece.screen_box(cam, m));
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
/// more): a box (a piece of a string), or a ball, whose screen box is worked out
/// exactly as well ([`ball_box`]).
#[derive(Debug, Clone, Copy)]
pub(crate) enum Piece {
    Box(Aabb),
    Ball(Vec3, f32),
}

impl Piece {
    /// Its screen box under `m` (`None`: every pixel).
    fn screen_box(&self, cam: &CameraRays, m: &Map) -> Option<[[f32; 2]; 2]> {
        match *self {
            Piece::Box(b) => screen_box(cam, &b, m),
            Piece::Ball(c, r) => {
                let b = Aabb {
                    min: c - Vec3::splat(r),
                    max: c + Vec3::splat(r),
                };
                // Both bound the image: the corners' box says it is in front and
                // bounded, the exact one is tighter.
                let [bx, by] = screen_box(cam, &b, m)?;
                let Some([ex, ey]) = ball_box(cam, (c, r), m) else {
                    return Some([bx, by]);
                };
                let meet = |a: [f32; 2], e: [f32; 2]| [a[0].max(e[0]), a[1].min(e[1])];
                Some([meet(bx, ex), meet(by, ey)])
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

/// A plane `n . x + d = 0` as `(n, d)`, in f64.
type Plane4 = (DVec3, f64);

/// The screen box of the image of the ball at `c` of radius `r` under `m`,
/// `[[x0, x1], [y0, y1]]` in pixels, from the screen lines that touch it: a
/// screen column (or row) is a plane through the eye, linear in the column's
/// place `s`; where a point of the ball shows in column `s`, that plane (for a
/// shadow, the plane through the light and the line where it cuts the plane
/// of the shadow; for a mirror image, the plane against the mirrored ball)
/// meets the ball, so `s` lies where the quadratic `dist^2 - r^2` (times the
/// normal's length squared) is not positive: between its roots. `None` where
/// that set is not an interval.
fn ball_box(cam: &CameraRays, (c, r): (Vec3, f32), m: &Map) -> Option<[[f32; 2]; 2]> {
    let d = |v: Vec3| v.as_dvec3();
    let (o, f, right, up) = (d(cam.origin), d(cam.forward), d(cam.right), d(cam.up));
    let mut c = d(c);
    // The cast's plane and light (homogeneous: w = 0 for a direction).
    let mut cast: Option<(Plane4, DVec3, f64)> = None;
    match *m {
        Map::Eye => {}
        Map::Mirror { point, normal } => {
            let (p, n) = (d(point), d(normal));
            c -= 2.0 * (c - p).dot(n) * n;
        }
        Map::Cast {
            point,
            normal,
            from,
        } => cast = Some(((d(normal), -d(normal).dot(d(point))), d(from), 1.0)),
        Map::Along {
            point,
            normal,
            along,
        } => cast = Some(((d(normal), -d(normal).dot(d(point))), d(along), 0.0)),
    }
    let through_eye = |n: DVec3| (n, -n.dot(o));
    // Column s: the plane through the eye holding `up` and `forward + right s`;
    // row s: the one holding `right` and `forward + up s`.
    let range = |(a, b): (Plane4, Plane4)| -> Option<[f64; 2]> {
        let at = |p: Plane4, x: DVec3, w: f64| p.0.dot(x) + p.1 * w;
        // Against the cast: the plane through the light and the line where
        // plane p cuts the plane of the shadow, p (pi . L) - pi (p . L).
        let lift = |p: Plane4| match cast {
            None => p,
            Some((pi, l, w)) => {
                let (k, j) = (at(pi, l, w), at(p, l, w));
                (p.0 * k - pi.0 * j, p.1 * k - pi.1 * j)
            }
        };
        let (a, b) = (lift(a), lift(b));
        let r2 = f64::from(r) * f64::from(r);
        let (a0, a1) = (at(a, c, 1.0), at(b, c, 1.0));
        let alpha = a1 * a1 - r2 * b.0.length_squared();
        let beta = 2.0 * (a0 * a1 - r2 * a.0.dot(b.0));
        let gamma = a0 * a0 - r2 * a.0.length_squared();
        let disc = beta * beta - 4.0 * alpha * gamma;
        // Not an interval (or a tiny, ill-conditioned one): the corners decide.
        if alpha <= 1e-9 * (a1 * a1 + r2 * b.0.length_squared()) || disc < 0.0 {
            return None;
        }
        let q = disc.sqrt();
        Some([(-beta - q) / (2.0 * alpha), (-beta + q) / (2.0 * alpha)])
    };
    let sx = range((through_eye(up.cross(f)), through_eye(up.cross(right))))?;
    let sy = range((through_eye(right.cross(f)), through_eye(right.cross(up))))?;
    let (w, h) = (f64::from(cam.width), f64::from(cam.height));
    let px = |s: f64| ((s + 1.0) * 0.5 * w) as f32;
    let py = |s: f64| ((1.0 - s) * 0.5 * h) as f32;
    Some([[px(sx[0]), px(sx[1])], [py(sy[1]), py(sy[0])]])
}

#[cfg(test)]
#[path = "screen_tests.rs"]
mod tests;
