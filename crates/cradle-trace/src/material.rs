//! The shading model's pieces, shared by the scalar reference and the lanes:
//! a surface's base colour (plain or checker), the Phong highlight with its
//! exponent made ready, the brightest radiance a scene can give and the
//! reflection bailout it sets.
//!
//! The reflection bailout is part of the model and applied identically everywhere:
//! a reflection is not traced when its weight (the product of `reflective` along the
//! path) times the brightest radiance the scene can produce times 12.92 (the
//! steepest slope of the sRGB curve) is below half an 8-bit step, 0.5/255. Its
//! contribution is then 0.

use super::geometry::floor_i64;
use super::scene::{Light, Material, Scene};
use glam::Vec3;

/// Half an 8-bit step, divided by the steepest slope of the sRGB encoding.
pub(crate) const BAILOUT: f32 = 0.5 / 255.0 / 12.92;

/// The scene's brightest possible radiance per channel: every light at full
/// diffuse and full specular, or the background.
#[must_use]
pub fn radiance_bound(scene: &Scene) -> f32 {
    let lights: Vec3 = scene
        .lights
        .iter()
        .map(|l| match *l {
            Light::Ambient { color } => color,
            Light::Point { color, .. } | Light::Directional { color, .. } => 2.0 * color,
        })
        .sum();
    lights.max(scene.background).max_element()
}

/// `x` to the power `n` (at least 1) by repeated squaring, lowest bits first:
/// the same multiplications in the same order for a float and for lanes of
/// floats. (Plain loops, no closure: inlined into the AVX2 build of the lanes.)
#[expect(
    clippy::inline_always,
    reason = "inlined into the lanes' AVX2 build, which a call would leave"
)]
#[inline(always)]
pub(crate) fn powi<T: Copy + std::ops::Mul<Output = T>>(x: T, n: u32) -> T {
    let mut base = x;
    for _ in 0..n.trailing_zeros() {
        base = base * base;
    }
    let mut out = base;
    let mut rest = n.checked_shr(n.trailing_zeros() + 1).unwrap_or(0);
    while rest != 0 {
        base = base * base;
        if rest & 1 != 0 {
            out = out * base;
        }
        rest >>= 1;
    }
    out
}

/// A whole-number Phong exponent (1..=10000, as every asset's is), for
/// [`powi`]; `None` for the others, which take `powf`.
#[inline]
#[must_use]
pub(crate) fn whole(exponent: f32) -> Option<u32> {
    // A conversion and back, not `fract` (a libm call in the portable build).
    let n = exponent as u32;
    ((1..=10_000).contains(&n) && n as f32 == exponent).then_some(n)
}

/// A material's Phong exponent made ready for [`highlight`]: whole (by
/// [`powi`]) or not, and the least `facing` whose highlight is kept.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Phong {
    /// The exponent.
    pub(crate) exponent: f32,
    /// It as a whole number, where it is one ([`whole`]).
    pub(crate) whole: Option<u32>,
    /// `(2^-100)^(1 / exponent)`: below it the highlight, under 2^-100, is 0.
    pub(crate) least: f32,
}

impl Phong {
    /// Exponent `exponent` made ready.
    #[must_use]
    pub(crate) fn new(exponent: f32) -> Self {
        let least = (2f64.powi(-100)).powf(1.0 / f64::from(exponent)) as f32;
        Self {
            exponent,
            whole: whole(exponent),
            least,
        }
    }
}

/// The Phong highlight `facing^exponent`: by [`powi`] for a whole-number
/// exponent (vectorizable, the same bits in lanes), else `powf`; 0 where
/// `facing` is below `least` (the highlight would be below 2^-100, far under
/// half an ulp of any lit colour). That cut keeps subnormal numbers out of the
/// squarings: an operation on them takes a slow microcode path on x86 CPUs.
#[inline]
#[must_use]
pub(crate) fn highlight(facing: f32, phong: Phong) -> f32 {
    if facing < phong.least {
        return 0.0;
    }
    match phong.whole {
        Some(n) => powi(facing, n),
        None => facing.powf(phong.exponent),
    }
}

/// The surface colour at `point`: plain, or a checker on the x-z grid.
pub(crate) fn base_color(m: &Material, point: Vec3) -> Vec3 {
    match m.checker {
        Some((other, size)) => {
            let cell = floor_i64(point.x / size) + floor_i64(point.z / size);
            if cell.rem_euclid(2) == 0 {
                m.color
            } else {
                other
            }
        }
        None => m.color,
    }
}
