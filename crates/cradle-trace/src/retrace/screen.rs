//! The motion filter's screen half: where on the picture a moved shape can
//! change a pixel through the pixel's free segments (`Record::segment`'s `free`), which
//! leave no cells. A camera ray comes near a shape only where the shape shows
//! on the screen; the mirror ray of a camera ray off a plane only where the
//! shape's mirror image in the plane shows; and a shadow ray from where a
//! camera ray met a plane only where the shape's shadow on the plane shows.
//! Each of those regions is bounded by the images of the corners of a box
//! around the shape (mirrored or cast onto the plane, then seen): for a ball
//! their screen box, met with the ball's exact one and, row by row, with its
//! ellipse (`conic`); for a string a rectangle along the image of its axis;
//! where the images reach behind the eye, the box of what of them lies in
//! front ([`CameraRays::hull_box`]). Padded, per row, [`Spans`] holds their union
//! as runs of pixels. `Moved::dirty` takes a pixel in a run as a candidate
//! whatever its cells.

use crate::camera::CameraRays;
use crate::geometry::Aabb;
use crate::scene::{Light, Scene, Shape};
use glam::Vec3;
use rayon::prelude::*;

mod ball;
mod conic;
mod rod;
use ball::ball_box;
use conic::Conic;
use rod::{band_x, rod_region};

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
    /// Within the runs, those of pixels whose centre sample lies well inside a
    /// ball's image or its mirror image (`sure_start` as `start`):
    /// [`Spans::sure_row`].
    sure: Vec<(u32, u32)>,
    sure_start: Vec<u32>,
}

impl Spans {
    /// The runs of the shapes within `pieces` seen by `cam` in `scene`
    /// (`None`: a shape without a box, so every pixel).
    pub(crate) fn new(cam: &CameraRays, scene: &Scene, pieces: Option<&[Piece]>) -> Self {
        let (w, h) = scene.size;
        let whole = Region::Box([[0.0, w as f32], [0.0, h as f32]]);
        // Each piece under each map, rasterized in parallel (a frame has
        // about a hundred; the runs are sorted by row after).
        let rows = match pieces {
            None => {
                let mut rows = Rows::default();
                rows.add(whole, false, (w, h));
                rows
            }
            Some(pieces) => {
                let maps = maps(scene);
                pieces
                    .par_iter()
                    .flat_map_iter(|piece| maps.iter().map(move |m| (piece, m)))
                    .fold(Rows::default, |mut rows, (piece, m)| {
                        let r = piece.region(cam, m).unwrap_or(whole);
                        rows.add(r, m.sure(), (w, h));
                        rows
                    })
                    .reduce(Rows::default, Rows::join)
            }
        };
        let (runs, start) = merged(rows.cover, h);
        let (sure, sure_start) = merged(rows.sure, h);
        Self {
            runs,
            start,
            sure,
            sure_start,
        }
    }

    /// Row `y`'s runs (none past the picture).
    pub(crate) fn row(&self, y: usize) -> &[(u32, u32)] {
        of_row(&self.runs, &self.start, y)
    }

    /// Row `y`'s runs of pixels whose centre sample lies inside a ball's image
    /// or its mirror image (its camera ray, or its mirror ray off the plane,
    /// meets the ball) by more than [`SURE_PX`]: such a pixel comes near the ball unless
    /// something hides it, so the filter takes it without reading its segments
    /// (one hidden is traced again needlessly, never wrongly).
    pub(crate) fn sure_row(&self, y: usize) -> &[(u32, u32)] {
        of_row(&self.sure, &self.sure_start, y)
    }

    /// The runs `cover` (row, x0, x1) of a picture `h` rows high, none of
    /// them sure: spans made by hand, for the filter's tests.
    #[cfg(test)]
    pub(crate) fn of_runs(cover: Vec<(u32, u32, u32)>, h: u32) -> Self {
        let (runs, start) = merged(cover, h);
        Self {
            runs,
            start,
            sure: Vec::new(),
            sure_start: vec![0; h as usize + 1],
        }
    }
}

/// Pixels a centre must lie inside a ball's image for [`Spans::sure_row`].
const SURE_PX: f32 = 1.0;

/// Row `y`'s runs of `runs` whose rows start at `start`.
fn of_row<'a>(runs: &'a [(u32, u32)], start: &[u32], y: usize) -> &'a [(u32, u32)] {
    match (start.get(y), start.get(y + 1)) {
        (Some(&a), Some(&b)) => &runs[a as usize..b as usize],
        _ => &[],
    }
}

/// Pixels `x0..x1` of rows `y` as `(y, x0, x1)`, in no order: what the
/// regions cover, and their sure parts ([`Spans::sure_row`]).
#[derive(Debug, Default)]
struct Rows {
    cover: Vec<(u32, u32, u32)>,
    sure: Vec<(u32, u32, u32)>,
}

impl Rows {
    /// Adds region `r` of a `w` x `h` picture (with its sure part if
    /// `sure_ok`), padded by [`PAD_PX`], clamped to the picture.
    fn add(&mut self, r: Region, sure_ok: bool, (w, h): (u32, u32)) {
        // Clamped to the picture (NaN to 0: `as` saturates).
        let px = |v: f32, n: u32| (v.max(0.0) as u32).min(n);
        match r {
            Region::Box([[x0, x1], [y0, y1]]) => {
                let (x0, x1) = (px((x0 - PAD_PX).floor(), w), px((x1 + PAD_PX).ceil(), w));
                let (y0, y1) = (px((y0 - PAD_PX).floor(), h), px((y1 + PAD_PX).ceil(), h));
                if x0 < x1 {
                    self.cover.extend((y0..y1).map(|y| (y, x0, x1)));
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
                            self.cover.push((y, l, r));
                        }
                    }
                    // The pixels whose centre lies inside the ellipse at the
                    // row's centre line by more than SURE_PX.
                    let mid = y as f32 + 0.5;
                    if let Some((l, r)) = conic.band_x((mid, mid)).filter(|_| sure_ok) {
                        let (l, r) = (l.max(x0) + SURE_PX - 0.5, r.min(x1) - SURE_PX - 0.5);
                        let (l, r) = (px(l.ceil(), w), px(r.floor() + 1.0, w));
                        if l < r {
                            self.sure.push((y, l, r));
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
                            self.cover.push((y, x0, x1));
                        }
                    }
                }
            }
        }
    }

    /// Both sets of rows in one.
    fn join(mut self, mut other: Self) -> Self {
        self.cover.append(&mut other.cover);
        self.sure.append(&mut other.sure);
        self
    }
}

/// The rows' runs of `cover` (row, x0, x1; rows below `h`) merged where they
/// meet, and where each row's begin (`h + 1` entries). Sorted by row with a
/// count per row, then each row's few by `x0`.
fn merged(cover: Vec<(u32, u32, u32)>, h: u32) -> (Vec<(u32, u32)>, Vec<u32>) {
    let h = h as usize;
    let mut at = vec![0u32; h + 1];
    for &(y, _, _) in &cover {
        at[y as usize + 1] += 1;
    }
    for y in 1..=h {
        at[y] += at[y - 1];
    }
    let mut sorted = vec![(0u32, 0u32); cover.len()];
    let mut next = at.clone();
    for &(y, x0, x1) in &cover {
        sorted[next[y as usize] as usize] = (x0, x1);
        next[y as usize] += 1;
    }
    let mut runs: Vec<(u32, u32)> = Vec::with_capacity(cover.len());
    let mut start = vec![0u32; h + 1];
    for y in 0..h {
        let row = &mut sorted[at[y] as usize..at[y + 1] as usize];
        row.sort_unstable();
        let first = runs.len();
        for &(x0, x1) in row.iter() {
            match runs[first..].last_mut() {
                Some(run) if x0 <= run.1 => run.1 = run.1.max(x1),
                _ => runs.push((x0, x1)),
            }
        }
        start[y + 1] = runs.len() as u32;
    }
    (runs, start)
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
                // Both bound the image: the box of the corners' images (all
                // of the maps keep straight lines straight, so the image of
                // the box is their hull's), and where the ball lies in front
                // of the eye the exact one, which is tighter.
                let images = corners(&b, m)?;
                let [bx, by] = cam.hull_box(&images);
                if !in_front(cam, &images) {
                    return Some(Region::Box([bx, by]));
                }
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

impl Map {
    /// Whether a pixel well inside a ball's image under the map is taken
    /// without its segments ([`Spans::sure_row`]): under the eye's and the
    /// mirror's, nearly always rightly (none of the default swing's pixels is
    /// traced needlessly); a shadow's interior held 860 pixels a frame that
    /// its segments would not have sent (hidden, or already in another
    /// shadow), which cost more to trace than their segments to test.
    fn sure(&self) -> bool {
        matches!(self, Map::Eye | Map::Mirror { .. })
    }
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

/// The images under `m` of the corners of `b`; `None` where one is unbounded.
fn corners(b: &Aabb, m: &Map) -> Option<[Vec3; 8]> {
    let mut out = b.corners();
    for p in &mut out {
        *p = apply(m, *p)?;
    }
    Some(out)
}

/// Whether every one of `points` lies in front of the eye, where
/// [`CameraRays::project`] places it.
fn in_front(cam: &CameraRays, points: &[Vec3; 8]) -> bool {
    points.iter().all(|&p| cam.project(p).is_some())
}

#[cfg(test)]
mod tests;
