//! Turning a scene into pixels: one function per pixel, rows in parallel with
//! rayon or serially; both run the same per-pixel code, so their bytes are equal.

use super::camera::CameraRays;
use super::geometry::Aabb;
use super::prepared::Prepared;
use super::scene::Scene;
use super::shade::{Cells, Motion, MotionGrid, radiance_bound, trace, trace_primary};
use super::tiles::Tiles;
use glam::Vec3;
use rayon::prelude::*;

/// An RGBA8 picture, sRGB-encoded, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height * 4` bytes.
    pub rgba: Vec<u8>,
}

/// `THRESHOLDS[b]` is the linear value at which the sRGB byte becomes `b + 1`: the
/// decoded midpoint `(b + 0.5) / 255`, computed in f64 once.
fn thresholds() -> &'static [f32; 255] {
    static T: std::sync::OnceLock<[f32; 255]> = std::sync::OnceLock::new();
    T.get_or_init(|| {
        std::array::from_fn(|b| {
            let s = (b as f64 + 0.5) / 255.0;
            let linear = if s <= 0.040_45 {
                s / 12.92
            } else {
                ((s + 0.055) / 1.055).powf(2.4)
            };
            linear as f32
        })
    })
}

/// Linear [0, 1] to an sRGB byte (IEC 61966-2-1), rounded to the nearest byte and
/// clamping out-of-range values: the count of decision points at or below the
/// value, found by binary search instead of a `powf` per channel.
#[must_use]
pub fn srgb8(linear: f32) -> u8 {
    // NaN counts as 0, like the clamp it replaces.
    thresholds().partition_point(|&t| t <= linear) as u8
}

/// Sub-pixel sample offsets: the pixel centre for one sample, else the first `n`
/// points of the R2 low-discrepancy sequence (the same for every pixel).
#[must_use]
pub fn sample_offsets(n: u32) -> Vec<(f32, f32)> {
    if n <= 1 {
        return vec![(0.5, 0.5)];
    }
    // Roberts' R2: steps by the inverse powers of the plastic number.
    const A1: f64 = 0.754_877_666_246_692_7;
    const A2: f64 = 0.569_840_290_998_053_3;
    (0..n)
        .map(|i| {
            (
                ((0.5 + A1 * f64::from(i)) % 1.0) as f32,
                ((0.5 + A2 * f64::from(i)) % 1.0) as f32,
            )
        })
        .collect()
}

/// Which work-skipping the renderer may use. Each leaves the picture byte for byte
/// as the full render makes it (tested); turning them off gives that reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderOptions {
    /// Primary rays test only the objects whose screen bounds cover their tile.
    pub tile_culling: bool,
    /// Shadow rays from a plane test only the objects whose shadow can fall there.
    pub shadow_culling: bool,
    /// Secondary rays walk a bounding volume hierarchy instead of every box.
    pub bvh: bool,
}

impl RenderOptions {
    /// Every skip on: what the app, `render` and `bench` use.
    pub const FAST: Self = Self {
        tile_culling: true,
        shadow_culling: true,
        bvh: true,
    };
    /// Nothing skipped: the reference the skips are tested against.
    pub const FULL: Self = Self {
        tile_culling: false,
        shadow_culling: false,
        bvh: false,
    };
}

/// Everything one row needs, shared by the serial and parallel paths.
struct Frame<'a> {
    prepared: Prepared<'a>,
    tiles: Option<Tiles>,
    camera: CameraRays,
    offsets: Vec<(f32, f32)>,
    bound: f32,
    width: u32,
    height: u32,
    motion: Option<MotionGrid>,
    /// Adaptive anti-aliasing: the byte difference above which a pixel is an edge.
    edge: Option<f32>,
}

impl<'a> Frame<'a> {
    /// `track`: note which pixels' rays enter the motion box (incremental frames only).
    fn new(scene: &'a Scene, options: RenderOptions, track: bool) -> Self {
        let prepared = Prepared::new(scene)
            .with_shadow_culling(options.shadow_culling)
            .with_bvh(options.bvh);
        let bound = radiance_bound(&prepared);
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
            motion: scene
                .motion_bounds
                .filter(|_| track)
                .map(|(min, max)| MotionGrid::new(Aabb { min, max })),
        }
    }

    /// The linear colour of pixel `(x, y)` from samples at `offsets`, and the
    /// motion cells its rays passed through.
    fn pixel(&self, x: u32, y: u32, offsets: &[(f32, f32)]) -> (Vec3, Cells) {
        let mut motion = Motion::new(self.motion);
        let sum: Vec3 = offsets
            .iter()
            .map(|&(dx, dy)| {
                let ray = self.camera.ray(x as f32 + dx, y as f32 + dy);
                match &self.tiles {
                    Some(t) => {
                        trace_primary(&self.prepared, &ray, t.at(x, y), self.bound, &mut motion)
                    }
                    None => trace(&self.prepared, &ray, 0, 1.0, self.bound, &mut motion),
                }
            })
            .sum();
        (sum / offsets.len() as f32, motion.mask)
    }

    fn put_with(&self, x: u32, y: u32, px: &mut [u8], offsets: &[(f32, f32)]) -> Cells {
        let (c, mask) = self.pixel(x, y, offsets);
        px.copy_from_slice(&[srgb8(c.x), srgb8(c.y), srgb8(c.z), 255]);
        mask
    }

    fn put(&self, x: u32, y: u32, px: &mut [u8]) -> Cells {
        self.put_with(x, y, px, &self.offsets)
    }

    /// Traces a whole row with `offsets`; returns each pixel's motion cells.
    fn row_with(&self, y: u32, out: &mut [u8], offsets: &[(f32, f32)]) -> Vec<Cells> {
        (0..self.width)
            .zip(out.chunks_exact_mut(4))
            .map(|(x, px)| self.put_with(x, y, px, offsets))
            .collect()
    }

    /// Whether pixel `(x, y)` of a one-sample picture differs from a 4-neighbour
    /// by more than `edge` in some channel.
    fn is_edge(&self, base: &[u8], x: u32, y: u32, edge: f32) -> bool {
        let at = |x: u32, y: u32| (y as usize * self.width as usize + x as usize) * 4;
        let here = &base[at(x, y)..at(x, y) + 3];
        let differs = |nx: u32, ny: u32| {
            let there = &base[at(nx, ny)..at(nx, ny) + 3];
            here.iter()
                .zip(there)
                .any(|(a, b)| f32::from(a.abs_diff(*b)) > edge)
        };
        (x > 0 && differs(x - 1, y))
            || (x + 1 < self.width && differs(x + 1, y))
            || (y > 0 && differs(x, y - 1))
            || (y + 1 < self.height && differs(x, y + 1))
    }

    /// The whole picture, rows in parallel or one after another (the same bytes):
    /// every pixel at every sample, or with adaptive anti-aliasing one centre
    /// sample first and then every sample at the edges of that picture. Returns it
    /// with each pixel's motion cells (row-major).
    fn image(&self, parallel: bool) -> (Image, Vec<Cells>) {
        let mut img = Image {
            width: self.width,
            height: self.height,
            rgba: vec![0; self.width as usize * self.height as usize * 4],
        };
        let Some(edge) = self.edge else {
            let masks = for_rows(&mut img, parallel, |y, row| {
                self.row_with(y, row, &self.offsets)
            });
            return (img, masks.concat());
        };
        let mut masks = for_rows(&mut img, parallel, |y, row| {
            self.row_with(y, row, &[(0.5, 0.5)])
        });
        let base = img.rgba.clone();
        let edges = for_rows(&mut img, parallel, |y, row| {
            (0..self.width)
                .zip(row.chunks_exact_mut(4))
                .map(|(x, px)| {
                    if self.is_edge(&base, x, y, edge) {
                        self.put(x, y, px)
                    } else {
                        0
                    }
                })
                .collect::<Vec<Cells>>()
        });
        for (m, e) in masks.iter_mut().zip(edges) {
            m.iter_mut().zip(e).for_each(|(a, b)| *a |= b);
        }
        (img, masks.concat())
    }
}

/// Runs `f(y, row)` over the rows of `img`, in parallel on the current rayon pool
/// or serially, and collects what it returns per row.
fn for_rows<R: Send>(
    img: &mut Image,
    parallel: bool,
    f: impl Fn(u32, &mut [u8]) -> R + Sync,
) -> Vec<R> {
    let stride = img.width as usize * 4;
    if parallel {
        img.rgba
            .par_chunks_exact_mut(stride)
            .enumerate()
            .map(|(y, row)| f(y as u32, row))
            .collect()
    } else {
        img.rgba
            .chunks_exact_mut(stride)
            .enumerate()
            .map(|(y, row)| f(y as u32, row))
            .collect()
    }
}

/// One row after another on this thread, with every skip: the serial twin of
/// [`render`].
#[must_use]
pub fn render_serial(scene: &Scene) -> Image {
    render_serial_with(scene, RenderOptions::FAST)
}

/// One row after another on this thread with the given skips;
/// `RenderOptions::FULL` is the reference renderer.
#[must_use]
pub fn render_serial_with(scene: &Scene, options: RenderOptions) -> Image {
    Frame::new(scene, options, false).image(false).0
}

/// Rows in parallel on the current rayon pool; byte-identical to [`render_serial`].
#[must_use]
pub fn render(scene: &Scene) -> Image {
    Frame::new(scene, RenderOptions::FAST, false).image(true).0
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
}

/// Renders frame after frame, re-tracing only what motion changed. Each pixel
/// keeps the cells of the motion grid (the box every moving object stays in, cut
/// 4 x 4 x 4) that its rays passed through. A frame re-traces only the pixels whose
/// cells meet those of the objects that moved since the frame before, where they
/// were and where they are: every other pixel's rays meet the same objects as when
/// it was traced, so it keeps its bytes. Every frame is byte-identical to a full
/// render (tested over 300-frame swings). Anything else changing (camera, lights,
/// size, a static object) brings a full frame.
#[derive(Debug, Default)]
pub struct Incremental {
    /// The scene of the last frame.
    last: Option<Scene>,
    image: Option<Image>,
    /// Per pixel, the motion cells its rays passed through when last traced.
    masks: Vec<Cells>,
    full: bool,
    /// Pixels re-traced by the last frame.
    retraced: usize,
}

/// The motion cells of the objects that moved from `before` to `after` (same
/// objects in the same order), where they were and where they are.
fn moved_cells(grid: &MotionGrid, before: &Scene, after: &Scene) -> Cells {
    before
        .objects
        .iter()
        .zip(&after.objects)
        .filter(|(a, b)| a.moving && a.shape != b.shape)
        .map(|(a, b)| {
            [&a.shape, &b.shape]
                .into_iter()
                .map(|s| {
                    super::prepared::bounds(s).map_or(Cells::MAX, |bx| grid.cells(bx.min, bx.max))
                })
                .fold(0, |m, c| m | c)
        })
        .fold(0, |m, c| m | c)
}

impl Incremental {
    /// A renderer with nothing cached: its first frame is full.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Renders `scene` on the current rayon pool and returns the picture.
    pub fn render(&mut self, scene: &Scene) -> &Image {
        let frame = Frame::new(scene, RenderOptions::FAST, true);
        // With adaptive anti-aliasing a pixel's sampling depends on its neighbours'
        // colours, which motion changes: those frames are traced in full.
        let reuse = scene.motion_bounds.is_some()
            && scene.adaptive.is_none_or(|_| scene.samples <= 1)
            && self.image.is_some()
            && self
                .last
                .as_ref()
                .is_some_and(|l| same_but_motion(l, scene));
        self.full = !reuse;
        match (reuse, frame.motion, self.last.as_ref()) {
            (true, Some(grid), Some(last)) => {
                let moved = moved_cells(&grid, last, scene);
                let img = self.image.as_mut().expect("checked above");
                let stride = img.width as usize * 4;
                self.retraced = img
                    .rgba
                    .par_chunks_exact_mut(stride)
                    .zip(self.masks.par_chunks_exact_mut(img.width as usize))
                    .enumerate()
                    .map(|(y, (row, masks))| {
                        let mut n = 0;
                        for (x, (px, m)) in row.chunks_exact_mut(4).zip(masks).enumerate() {
                            if *m & moved != 0 {
                                *m = frame.put(x as u32, y as u32, px);
                                n += 1;
                            }
                        }
                        n
                    })
                    .sum();
            }
            _ => {
                let (img, masks) = frame.image(true);
                self.retraced = masks.len();
                self.masks = masks;
                self.image = Some(img);
                self.full = true;
            }
        }
        self.last = Some(scene.clone());
        self.image.as_ref().expect("rendered above")
    }

    /// The last picture rendered.
    #[must_use]
    pub fn image(&self) -> Option<&Image> {
        self.image.as_ref()
    }

    /// Whether the last frame was traced in full.
    #[must_use]
    pub fn last_was_full(&self) -> bool {
        self.full
    }

    /// Share of pixels the last frame re-traced (0..=1).
    #[must_use]
    pub fn dynamic_share(&self) -> f64 {
        let total = self
            .image
            .as_ref()
            .map_or(1, |i| (i.width * i.height) as usize);
        self.retraced as f64 / total.max(1) as f64
    }
}

/// A rayon pool of `threads` workers (0: one per core).
///
/// # Errors
/// When the operating system refuses the threads.
pub fn pool(threads: usize) -> Result<rayon::ThreadPool, rayon::ThreadPoolBuildError> {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build()
}
