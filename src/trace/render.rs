//! Turning a scene into pixels: one function per pixel, rows in parallel with
//! rayon or serially; both run the same per-pixel code, so their bytes are equal.

use super::camera::CameraRays;
use super::geometry::Aabb;
use super::prepared::Prepared;
use super::scene::Scene;
use super::shade::{Motion, radiance_bound, trace, trace_primary};
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
}

impl RenderOptions {
    /// Every skip on: what the app, `render` and `bench` use.
    pub const FAST: Self = Self { tile_culling: true };
    /// Nothing skipped: the reference the skips are tested against.
    pub const FULL: Self = Self {
        tile_culling: false,
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
    motion: Option<Aabb>,
    /// Adaptive anti-aliasing: the byte difference above which a pixel is an edge.
    edge: Option<f32>,
}

impl<'a> Frame<'a> {
    /// `track`: note which pixels' rays enter the motion box (incremental frames only).
    fn new(scene: &'a Scene, options: RenderOptions, track: bool) -> Self {
        let prepared = Prepared::new(scene);
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
                .map(|(min, max)| Aabb { min, max }),
        }
    }

    /// The linear colour of pixel `(x, y)` from samples at `offsets`, and whether
    /// any of its rays entered the moving objects' box.
    fn pixel(&self, x: u32, y: u32, offsets: &[(f32, f32)]) -> (Vec3, bool) {
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
        (sum / offsets.len() as f32, motion.touched)
    }

    fn put_with(&self, x: u32, y: u32, px: &mut [u8], offsets: &[(f32, f32)]) -> bool {
        let (c, touched) = self.pixel(x, y, offsets);
        px.copy_from_slice(&[srgb8(c.x), srgb8(c.y), srgb8(c.z), 255]);
        touched
    }

    fn put(&self, x: u32, y: u32, px: &mut [u8]) -> bool {
        self.put_with(x, y, px, &self.offsets)
    }

    /// Traces a whole row; returns the pixels whose rays entered the motion box.
    fn row(&self, y: u32, out: &mut [u8]) -> Vec<u32> {
        (0..self.width)
            .zip(out.chunks_exact_mut(4))
            .filter_map(|(x, px)| self.put(x, y, px).then_some(x))
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
    /// with, per row, the pixels whose rays entered the motion box.
    fn image(&self, parallel: bool) -> (Image, Vec<Vec<u32>>) {
        let mut img = Image {
            width: self.width,
            height: self.height,
            rgba: vec![0; self.width as usize * self.height as usize * 4],
        };
        let Some(edge) = self.edge else {
            let touched = for_rows(&mut img, parallel, |y, row| self.row(y, row));
            return (img, touched);
        };
        let centre = [(0.5, 0.5)];
        let mut touched: Vec<Vec<u32>> = for_rows(&mut img, parallel, |y, row| {
            (0..self.width)
                .zip(row.chunks_exact_mut(4))
                .filter_map(|(x, px)| self.put_with(x, y, px, &centre).then_some(x))
                .collect()
        });
        let base = img.rgba.clone();
        let edges = for_rows(&mut img, parallel, |y, row| {
            (0..self.width)
                .zip(row.chunks_exact_mut(4))
                .filter(|(x, _)| self.is_edge(&base, *x, y, edge))
                .filter_map(|(x, px)| self.put(x, y, px).then_some(x))
                .collect::<Vec<u32>>()
        });
        for (t, e) in touched.iter_mut().zip(edges) {
            t.extend(e);
            t.sort_unstable();
            t.dedup();
        }
        (img, touched)
    }

    /// Traces only pixels `xs` of a row.
    fn some(&self, y: u32, xs: &[u32], out: &mut [u8]) {
        for &x in xs {
            let i = x as usize * 4;
            self.put(x, y, &mut out[i..i + 4]);
        }
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

/// The scene with the moving objects' shapes left out: while it stays the same, a
/// pixel whose rays never entered the motion box keeps its bytes.
fn static_part(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    for o in s.objects.iter_mut().filter(|o| o.moving) {
        o.shape = super::scene::Shape::Sphere {
            centre: Vec3::ZERO,
            radius: 0.0,
        };
    }
    s
}

/// Renders frame after frame, re-tracing only what motion can change: after a full
/// frame, only the pixels whose rays entered the box that holds every moving object
/// (`Scene::motion_bounds`). Every frame is byte-identical to a full render: the
/// other pixels' rays meet no moving object, and the rest of the scene is the same.
/// Anything else changing (camera, lights, size, a static object) brings a full frame.
#[derive(Debug, Default)]
pub struct Incremental {
    key: Option<Scene>,
    image: Option<Image>,
    /// Per row, the pixels to re-trace.
    dynamic: Vec<Vec<u32>>,
    full: bool,
}

impl Incremental {
    /// A renderer with nothing cached: its first frame is full.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Renders `scene` on the current rayon pool and returns the picture.
    pub fn render(&mut self, scene: &Scene) -> &Image {
        let key = static_part(scene);
        let frame = Frame::new(scene, RenderOptions::FAST, true);
        // With adaptive anti-aliasing a pixel's sampling depends on its neighbours'
        // colours, which motion changes: those frames are traced in full.
        let reuse = scene.motion_bounds.is_some()
            && scene.adaptive.is_none_or(|_| scene.samples <= 1)
            && self.image.is_some()
            && self.key.as_ref() == Some(&key);
        self.full = !reuse;
        if reuse {
            let img = self.image.as_mut().expect("checked above");
            let stride = img.width as usize * 4;
            img.rgba
                .par_chunks_exact_mut(stride)
                .zip(self.dynamic.par_iter())
                .enumerate()
                .for_each(|(y, (row, xs))| {
                    if !xs.is_empty() {
                        frame.some(y as u32, xs, row);
                    }
                });
        } else {
            let (img, dynamic) = frame.image(true);
            self.dynamic = dynamic;
            self.image = Some(img);
            self.key = Some(key);
        }
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

    /// Share of pixels re-traced in frames after a full one (0..=1).
    #[must_use]
    pub fn dynamic_share(&self) -> f64 {
        let n: usize = self.dynamic.iter().map(Vec::len).sum();
        let total = self
            .image
            .as_ref()
            .map_or(1, |i| (i.width * i.height) as usize);
        n as f64 / total.max(1) as f64
    }
}

/// A rayon pool of `threads` workers (0: one per core).
///
/// # Errors
/// When the operating system refuses the threads.
pub fn pool(threads: usize) -> Result<rayon::ThreadPool, rayon::ThreadPoolBuildError> {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build()
}
