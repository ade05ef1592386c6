//! Incremental frames for the window and sequences: each frame re-traces only the
//! pixels whose rays passed where moving objects were or are, and keeps every
//! other pixel's bytes, so the result equals a full render byte for byte.

use super::adaptive::Layers;
use super::adaptive::{adaptive_full, adaptive_next};
use super::camera::CameraRays;
use super::casters::Casters;
use super::color::Image;
use super::frame::{Frame, RenderOptions};
use super::geometry::{Aabb, bounds};
use super::motion::RowMotion;
use super::motion::{Cells, HITS, MET, MotionGrid, Near, NearSet, moving_bits};
use super::prepared::{Kept, PerPlane};
use super::render::image;
use super::retrace::{Moved, Piece, Spans, retrace_row};
use super::scene::{Light, Scene, Shape};
use glam::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// The next picture's number, over every renderer of the process, so that a
/// number names one picture ([`Changes`]).
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// Which bytes the last frame may have changed, for a consumer that keeps a copy
/// of the picture (the window's framebuffer): copying `rows` from the picture
/// numbered `since` gives the picture numbered `id`.
#[derive(Debug, Clone, Copy)]
pub struct Changes<'a> {
    /// The picture's number (unique in the process).
    pub id: u64,
    /// The number of the picture the frame started from; `None` after a full
    /// frame (every pixel may have changed).
    pub since: Option<u64>,
    /// Per row, the pixels `x0..x1` that may have changed (`[0, 0]`: none);
    /// every other byte equals picture `since`'s.
    pub rows: &'a [[u32; 2]],
}

/// The last picture of a renderer and which bytes its frame changed: what
/// [`Incremental`] keeps of its last frame, and lends out
/// ([`Incremental::lend`]) so that another thread reads it while the renderer
/// prepares its next frame ([`Incremental::render_lent`]), which takes it back
/// before it writes a pixel: the window copies the picture's changes to its
/// framebuffer while the next frame's set-up runs, not before it starts.
#[derive(Debug)]
pub struct Lent {
    image: Image,
    /// Per row, the pixels the frame may have changed ([`Changes::rows`]).
    written: Vec<[u32; 2]>,
    /// The picture's number and the one it started from ([`Changes`]).
    id: u64,
    since: Option<u64>,
}

impl Lent {
    /// The picture.
    #[must_use]
    pub fn image(&self) -> &Image {
        &self.image
    }

    /// Which bytes its frame may have changed.
    #[must_use]
    pub fn changes(&self) -> Changes<'_> {
        Changes::of(self.id, self.since, &self.written)
    }

    /// Picture `id`, traced whole (no picture before it to change).
    fn whole(image: Image, id: u64) -> Self {
        Self {
            image,
            written: Vec::new(),
            id,
            since: None,
        }
    }
}

impl<'a> Changes<'a> {
    /// Picture `id`'s changes from picture `since`, `written` per row (read
    /// only when there is a `since`).
    fn of(id: u64, since: Option<u64>, written: &'a [[u32; 2]]) -> Self {
        Self {
            id,
            since,
            rows: if since.is_some() { written } else { &[] },
        }
    }
}

/// What changed since the frame a renderer traced last, as its caller knows it
/// (the app's ECS, from the transforms its physics changed): the renderer
/// re-traces around the objects named and keeps every other pixel, so the
/// change must name every object that may have moved.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Change {
    /// Only the shapes of these moving objects (indices into the scene's
    /// objects) may differ; everything else is as it was.
    Moved(Vec<usize>),
    /// Anything may differ: the next frame is traced in full.
    Any,
}

impl Default for Change {
    /// Nothing is known: [`Change::Any`].
    fn default() -> Self {
        Self::Any
    }
}

impl Change {
    /// Nothing changed.
    #[must_use]
    pub fn none() -> Self {
        Self::Moved(Vec::new())
    }

    /// What changed over this change and then `next`.
    pub fn merge(&mut self, next: Self) {
        match (&mut *self, next) {
            (Self::Moved(a), Self::Moved(b)) => {
                a.extend(b);
                a.sort_unstable();
                a.dedup();
            }
            (_, Self::Any) => *self = Self::Any,
            (Self::Any, Self::Moved(_)) => {}
        }
    }

    /// The moving objects of `after` whose shapes changed from `before` (the
    /// same objects in the same order), when the two differ in nothing else
    /// ([`Change::Any`] otherwise): the change found by comparing two scenes.
    #[must_use]
    pub fn between(before: &Scene, after: &Scene) -> Self {
        if !same_but_motion(before, after) {
            return Self::Any;
        }
        Self::Moved(
            before
                .objects
                .iter()
                .zip(&after.objects)
                .enumerate()
                .filter(|(_, (a, b))| a.moving && a.shape != b.shape)
                .map(|(i, _)| i)
                .collect(),
        )
    }
}

/// Whether `a` and `b` differ at most in the shapes of their moving objects: then
/// a pixel whose rays met no moving object keeps its bytes. Every field is named,
/// so a new one cannot be forgotten here.
fn same_but_motion(a: &Scene, b: &Scene) -> bool {
    let Scene {
        objects,
        lights,
        camera,
        background,
        size,
        max_depth,
        samples,
        adaptive,
        motion_bounds,
        coarse,
    } = a;
    objects.len() == b.objects.len()
        && objects.iter().zip(&b.objects).all(|(o, p)| {
            o.moving == p.moving && o.material == p.material && (o.moving || o.shape == p.shape)
        })
        && *lights == b.lights
        && *camera == b.camera
        && *background == b.background
        && *size == b.size
        && *max_depth == b.max_depth
        && *samples == b.samples
        && *adaptive == b.adaptive
        && *motion_bounds == b.motion_bounds
        && *coarse == b.coarse
}

/// A frame's shadow casters and footprints, and the lights they were found
/// for, kept for the next frame.
#[derive(Debug)]
struct Culling {
    casters: Vec<Option<Casters>>,
    footprints: Option<PerPlane>,
    lights: Vec<Light>,
}

/// Renders frame after frame, re-tracing only what motion changed. Each pixel
/// keeps the cells of the motion grid (the box every moving object stays in, cut
/// 32 x 2 x 1, see `motion`) that its rays passed through, the moving objects
/// they met and its rays' segments in the box. A frame re-traces only the pixels
/// whose rays met an object that moved since the frame before, where it was, and
/// those one of whose segments comes near a moved object where it is now (found
/// through their cells and the screen's runs, `retrace`): every other pixel's
/// rays meet the same objects as when it was traced, so it keeps its bytes.
/// Every frame is byte-identical to a full render (tested over 300-frame
/// swings). Anything else changing (camera, lights, size, a static object)
/// brings a full frame.
#[derive(Debug, Default)]
pub struct Incremental {
    /// The scene of the last frame, kept by [`Self::render`] to find the
    /// change by comparing.
    last: Option<Scene>,
    /// The objects' shapes in the last frame: where the moved ones were.
    shapes: Vec<Shape>,
    /// The last picture and its changes (`None` before the first, and while
    /// it is lent out).
    picture: Option<Lent>,
    /// Per row, each pixel's motion cells and segments when last traced.
    rows: Vec<RowMotion>,
    full: bool,
    /// Pixels re-traced by the last frame.
    retraced: usize,
    /// With adaptive anti-aliasing: the layers its frames keep (then `rows` is
    /// unused).
    layers: Option<Layers>,
    /// The last frame's shadow culling: the next frame keeps what still
    /// holds ([`Kept`]).
    culling: Option<Culling>,
}

/// The objects of `list` that moved from `before` (their shapes in the last
/// frame) to `after`: their bits among the moving objects (a pixel any of
/// whose rays met one of them, where it was, is traced again: at once where
/// no object that stayed shares the bit, else where one of its segments
/// comes near such an object's old place), and where they
/// are: their motion cells and shapes, and where `cam` sees them, their mirror
/// images and their shadows (`Spans`), for the pixels whose rays they may
/// meet now.
fn moved(
    grid: &MotionGrid,
    cam: &CameraRays,
    (before, after): (&[Shape], &Scene),
    list: &[usize],
) -> Moved {
    let mut out = Moved {
        lo: Vec3::INFINITY,
        hi: Vec3::NEG_INFINITY,
        ..Moved::default()
    };
    let bits = moving_bits(&after.objects);
    let mut nears = Vec::new();
    let mut pieces = Vec::new();
    let mut moved = vec![false; bits.len()];
    let mut was = Vec::new();
    for &i in list {
        let is = &after.objects[i].shape;
        if before[i] == *is {
            continue;
        }
        moved[i] = true;
        out.cells |= bits[i] | bits[i] << 32;
        if let Some(n) = Near::of(&before[i]) {
            was.push((bits[i], n));
        }
        if let (Shape::Sphere { centre: c0, .. }, Shape::Sphere { centre, radius }) =
            (before[i], *is)
        {
            out.balls.push((c0, centre, radius, bits[i] << 32));
        }
        let cells = shape_cells(grid, is) & !HITS;
        out.cells |= cells;
        near_pieces(is, &mut pieces);
        if let Some(n) = Near::of(is) {
            (out.lo, out.hi) = (out.lo.min(n.lo()), out.hi.max(n.hi()));
            nears.push((cells, n));
        } else {
            // A moving plane (none is): every segment may meet it.
            out.cells = Cells::MAX;
            out.coarse = true;
        }
    }
    out.near = NearSet::new(nears);
    // The bits some object that did not move shares: a pixel with one of
    // those is taken only where its segments met a moved object's old place.
    let still = (bits.iter().zip(&moved))
        .filter(|&(_, &m)| !m)
        .fold(0, |a, (&b, _)| a | b);
    out.sure = out.cells & MET & !still;
    // The moved balls' shadow bits that no other ball holds.
    let ball = |i: usize| matches!(after.objects[i].shape, Shape::Sphere { .. });
    let shared = (0..bits.len())
        .filter(|&i| ball(i))
        .fold((0, 0), |(once, more), i| {
            (once | bits[i], more | (once & bits[i]))
        });
    out.sole = (out.balls.iter()).fold(0, |a, b| a | b.3) & !(shared.1 << 32);
    was.retain(|&(b, _)| b & still != 0);
    out.was = was;
    out.spans = Spans::new(cam, after, (!out.coarse).then_some(&pieces[..]));
    out
}

/// Pieces around `shape` grown as [`Near::of`] grows its box, appended to
/// `out`: a ball, or a string or rod whole (on the screen, a band along the
/// image of its axis).
fn near_pieces(shape: &super::scene::Shape, out: &mut Vec<Piece>) {
    use super::scene::Shape;
    match *shape {
        Shape::Cylinder { a, b, radius } => out.push(Piece::Rod(a, b, radius + 2.0 * Near::PAD)),
        Shape::Sphere { centre, radius } => out.push(Piece::Ball(centre, radius + 2.0 * Near::PAD)),
        Shape::Plane { .. } => {}
    }
}

/// The cells `shape` overlaps: a cylinder's as the cells of 8 pieces along it,
/// so a thin slanted string claims a band of cells, not its whole bounding box.
fn shape_cells(grid: &MotionGrid, shape: &super::scene::Shape) -> Cells {
    if let super::scene::Shape::Cylinder { a, b, radius } = *shape {
        let r = glam::Vec3::splat(radius);
        return (0..8)
            .map(|i| {
                let p = a.lerp(b, i as f32 / 8.0);
                let q = a.lerp(b, (i + 1) as f32 / 8.0);
                grid.cells(p.min(q) - r, p.max(q) + r)
            })
            .fold(0, |m, c| m | c);
    }
    super::geometry::bounds(shape).map_or(Cells::MAX, |bx| grid.cells(bx.min, bx.max))
}

impl Incremental {
    /// A renderer with nothing cached: its first frame is full.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Renders `scene` on the current rayon pool and returns the picture,
    /// finding what changed by comparing it with the last frame's scene
    /// ([`Change::between`]).
    pub fn render(&mut self, scene: &Scene) -> &Image {
        let change = self
            .last
            .as_ref()
            .map_or(Change::Any, |last| Change::between(last, scene));
        self.render_changed(scene, &change);
        self.last = Some(scene.clone());
        &self.picture.as_ref().expect("rendered above").image
    }

    /// Renders `scene` on the current rayon pool, `change` saying what changed
    /// since the last frame this renderer traced, and returns the picture.
    pub fn render_changed(&mut self, scene: &Scene, change: &Change) -> &Image {
        self.render_lent(scene, change, || None)
    }

    /// Lends the last picture out (`None` before the first): until
    /// [`Self::render_lent`] takes it back, the renderer holds no picture.
    pub fn lend(&mut self) -> Option<Lent> {
        self.picture.take()
    }

    /// [`Self::render_changed`] when the last picture is lent out
    /// ([`Self::lend`]): the frame is prepared (its culling, what moved and
    /// where it shows), then `back` gives the picture back (it may wait for
    /// its reader) and the frame traces into it. Without it back (`None`), the
    /// frame is traced in full.
    pub fn render_lent(
        &mut self,
        scene: &Scene,
        change: &Change,
        back: impl FnOnce() -> Option<Lent>,
    ) -> &Image {
        self.last = None;
        if scene.coarse > 1 {
            return self.render_coarse(scene);
        }
        // The moved objects, if the change is one this renderer can follow.
        let list = match change {
            Change::Moved(list)
                if self.shapes.len() == scene.objects.len()
                    && list
                        .iter()
                        .all(|&i| scene.objects.get(i).is_some_and(|o| o.moving)) =>
            {
                Some(&list[..])
            }
            _ => None,
        };
        // What moved since the last frame, found while the frame is prepared
        // (from the same camera and grid as the frame's).
        let kept = self.kept(scene, list);
        let (mut frame, moved) = rayon::join(
            || Frame::with_kept(scene, RenderOptions::FAST, true, kept),
            || {
                let (min, max) = scene.motion_bounds?;
                let grid = MotionGrid::new(Aabb { min, max });
                let cam = CameraRays::new(&scene.camera, scene.size.0, scene.size.1);
                Some(moved(&grid, &cam, (&self.shapes, scene), list?))
            },
        );
        if self.picture.is_none() {
            self.picture = back();
        }
        let adaptive = frame.edge();
        let reuse = self.picture.is_some() && adaptive.is_some() == self.layers.is_some();
        self.full = !reuse;
        let id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
        if let (true, Some(moved), Some(pic)) = (reuse, moved, self.picture.as_mut()) {
            let img = &mut pic.image;
            pic.written.resize(img.height as usize, [0, 0]);
            if let (Some(threshold), Some(layers)) = (adaptive, self.layers.as_mut()) {
                let out = (img, &mut pic.written[..]);
                self.retraced = adaptive_next(&frame, threshold, layers, out, &moved);
            } else {
                let (stride, w) = (img.width as usize * 4, img.width);
                self.retraced = img
                    .rgba
                    .par_chunks_exact_mut(stride)
                    .zip(self.rows.par_iter_mut())
                    .zip(pic.written.par_iter_mut())
                    .enumerate()
                    .map(|(y, ((row, rm), written))| {
                        let at = (&moved, frame.offsets());
                        let n = retrace_row(&frame, y as u32, row, rm, at, None);
                        // A traced row may have changed anywhere in its runs.
                        *written = if n > 0 { [0, w] } else { [0, 0] };
                        n
                    })
                    .sum();
            }
            (pic.since, pic.id) = (Some(pic.id), id);
            for &i in list.unwrap_or_default() {
                self.shapes[i] = scene.objects[i].shape;
            }
        } else {
            let (img, rows, layers) = if let Some(threshold) = adaptive {
                let (img, layers) = adaptive_full(&frame, threshold, (true, None));
                (img, Vec::new(), Some(layers))
            } else {
                let (img, rows) = image(&frame, true);
                (img, rows, None)
            };
            self.retraced = img.width as usize * img.height as usize;
            self.rows = rows;
            self.layers = layers;
            self.picture = Some(Lent::whole(img, id));
            self.full = true;
            self.shapes = scene.objects.iter().map(|o| o.shape).collect();
        }
        self.culling = frame.take_culling().map(|(casters, footprints)| Culling {
            casters,
            footprints,
            lights: scene.lights.clone(),
        });
        &self.picture.as_ref().expect("rendered above").image
    }

    /// What the next frame, of `scene` with the objects of `list` moved since
    /// the last one, may keep of the last frame's shadow culling: nothing
    /// unless the change is one this renderer follows, the lights are the
    /// same and every moved object has a box.
    fn kept(&mut self, scene: &Scene, list: Option<&[usize]>) -> Option<Kept> {
        let Culling {
            casters,
            footprints,
            lights,
        } = self.culling.take()?;
        let list = list?;
        if lights != scene.lights {
            return None;
        }
        let mut boxes = Vec::with_capacity(2 * list.len());
        for &i in list {
            boxes.push(bounds(self.shapes.get(i)?)?);
            boxes.push(bounds(&scene.objects.get(i)?.shape)?);
        }
        Some(Kept {
            casters,
            footprints,
            moved: list.to_vec(),
            boxes,
        })
    }

    /// A frame at one ray per block ([`Scene::coarse`]): traced afresh and
    /// stretched, and nothing kept for the next frame, which is full.
    fn render_coarse(&mut self, scene: &Scene) -> &Image {
        let img = crate::render::render(scene);
        let (w, h) = crate::render::coarse_size(scene.size, scene.coarse);
        self.retraced = w as usize * h as usize;
        self.full = true;
        self.shapes.clear();
        self.culling = None;
        self.rows.clear();
        self.layers = None;
        let id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
        &self.picture.insert(Lent::whole(img, id)).image
    }

    /// Which bytes the last frame may have changed (`None` before the first).
    #[must_use]
    pub fn changes(&self) -> Option<Changes<'_>> {
        self.picture.as_ref().map(Lent::changes)
    }

    /// The last picture rendered.
    #[must_use]
    pub fn image(&self) -> Option<&Image> {
        self.picture.as_ref().map(Lent::image)
    }

    /// Whether the last frame was traced in full.
    #[must_use]
    pub fn last_was_full(&self) -> bool {
        self.full
    }

    /// Share of pixels the last frame re-traced (0..=1).
    #[must_use]
    pub fn dynamic_share(&self) -> f64 {
        let total = self.image().map_or(1, |i| (i.width * i.height) as usize);
        self.retraced as f64 / total.max(1) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::shape_cells;
    use crate::geometry::Aabb;
    use crate::motion::MotionGrid;
    use crate::scene::Shape;
    use glam::Vec3;

    #[test]
    fn a_slanted_string_claims_a_band_of_cells_that_covers_it() {
        let grid = MotionGrid::new(Aabb {
            min: Vec3::new(-0.2, 0.0, -0.05),
            max: Vec3::new(0.2, 0.25, 0.05),
        });
        let (a, b) = (Vec3::new(-0.15, 0.24, 0.04), Vec3::new(0.1, 0.02, 0.0));
        let string = Shape::Cylinder {
            a,
            b,
            radius: 0.0006,
        };
        let band = shape_cells(&grid, &string);
        // Every point of the axis lies in a claimed cell.
        for i in 0..=1000 {
            let p = a.lerp(b, i as f32 / 1000.0);
            let cell = grid.cells(p, p);
            assert_eq!(cell & !band, 0, "point {i} outside the band");
        }
        // And the band is well under the bounding box's cells (here 22 of 32
        // columns times 2 rows, 44): at most two thirds of them.
        let boxed = grid.cells(a.min(b), a.max(b));
        assert!(
            band.count_ones() * 3 <= boxed.count_ones() * 2,
            "{} of {}",
            band.count_ones(),
            boxed.count_ones()
        );
    }
}
