//! Lane vectors: three lane values of one lane build (`S: Simd`), a vector per
//! lane, with the vector operations of glam's `Vec3` in its order (a dot product
//! is `(x * x') + (y * y') + z * z'`), and the packet's floor hits in them.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::LANES;
use crate::simd::Simd;
use glam::Vec3;
use std::ops::{Add, Div, Mul, Neg, Sub};

pub(super) type F8 = [f32; LANES];

/// Eight vectors, one per lane.
#[derive(Clone, Copy)]
pub(super) struct V8 {
    pub(super) x: F8,
    pub(super) y: F8,
    pub(super) z: F8,
}

/// The lanes `f(0)..f(7)`. A plain loop, which inlines and vectorizes;
/// `std::array::from_fn` calls its closure through a wrapper that stays a call.
#[inline(always)]
pub(super) fn f8(f: impl FnMut(usize) -> f32) -> F8 {
    lanes(f)
}

/// [`f8`] for any lane type.
#[inline(always)]
pub(super) fn lanes<T: Copy + Default>(mut f: impl FnMut(usize) -> T) -> [T; LANES] {
    let mut out = [T::default(); LANES];
    for (i, o) in out.iter_mut().enumerate() {
        *o = f(i);
    }
    out
}

/// The lanes of `among` (bits) whose `keys` equal `key`. (A plain loop, no
/// closure: it inlines into the AVX2 build.)
#[inline(always)]
pub(super) fn lanes_with<T: PartialEq>(keys: &[T; LANES], key: &T, among: u8) -> u8 {
    let mut bits = 0u8;
    for (i, k) in keys.iter().enumerate() {
        if k == key {
            bits |= 1 << i;
        }
    }
    bits & among
}

impl V8 {
    pub(super) const ZERO: V8 = V8 {
        x: [0.0; LANES],
        y: [0.0; LANES],
        z: [0.0; LANES],
    };

    #[inline(always)]
    pub(super) fn lane(&self, i: usize) -> Vec3 {
        Vec3::new(self.x[i], self.y[i], self.z[i])
    }

    /// Sets lane `i` to `v`.
    pub(super) fn set(&mut self, i: usize, v: Vec3) {
        (self.x[i], self.y[i], self.z[i]) = (v.x, v.y, v.z);
    }
}

/// Three lane values of build `S`: a vector per lane.
#[derive(Clone, Copy)]
pub(super) struct L3<F> {
    pub(super) x: F,
    pub(super) y: F,
    pub(super) z: F,
}

impl<F> L3<F>
where
    F: Copy
        + Add<Output = F>
        + Sub<Output = F>
        + Mul<Output = F>
        + Div<Output = F>
        + Neg<Output = F>,
{
    /// `a.dot(b)`: `(a.x * b.x) + (a.y * b.y) + (a.z * b.z)`.
    #[inline(always)]
    pub(super) fn dot(&self, b: &Self) -> F {
        (self.x * b.x) + (self.y * b.y) + (self.z * b.z)
    }

    /// `v * k`, per component.
    #[inline(always)]
    pub(super) fn scale(&self, k: F) -> Self {
        L3 {
            x: self.x * k,
            y: self.y * k,
            z: self.z * k,
        }
    }

    /// `a - b`, per component.
    #[inline(always)]
    pub(super) fn sub(&self, b: &Self) -> Self {
        L3 {
            x: self.x - b.x,
            y: self.y - b.y,
            z: self.z - b.z,
        }
    }

    /// `a * b`, per component.
    #[inline(always)]
    pub(super) fn mul(&self, b: &Self) -> Self {
        L3 {
            x: self.x * b.x,
            y: self.y * b.y,
            z: self.z * b.z,
        }
    }

    /// `v / k`, per component.
    #[inline(always)]
    pub(super) fn div(&self, k: F) -> Self {
        L3 {
            x: self.x / k,
            y: self.y / k,
            z: self.z / k,
        }
    }

    /// `-v`.
    #[inline(always)]
    pub(super) fn neg(&self) -> Self {
        L3 {
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }

    /// `a + b`, per component.
    #[inline(always)]
    pub(super) fn add(&self, b: &Self) -> Self {
        L3 {
            x: self.x + b.x,
            y: self.y + b.y,
            z: self.z + b.z,
        }
    }
}

/// The lanes' hits on the floor.
pub(super) struct Surface<F> {
    /// The rays' directions.
    pub(super) d: L3<F>,
    /// Where they meet the floor.
    pub(super) point: L3<F>,
    /// The secondary rays' origin, off the surface.
    pub(super) start: L3<F>,
    /// The normal, facing the rays.
    pub(super) nn: L3<F>,
}

/// `v` in every lane.
#[inline(always)]
pub(super) fn splat3<S: Simd>(s: S, v: Vec3) -> L3<S::F> {
    L3 {
        x: s.splat(v.x),
        y: s.splat(v.y),
        z: s.splat(v.z),
    }
}

/// `a` in the lanes of `m`, `b` in the others.
#[inline(always)]
pub(super) fn select3<S: Simd>(m: S::M, a: &L3<S::F>, b: &L3<S::F>) -> L3<S::F> {
    L3 {
        x: S::select(m, a.x, b.x),
        y: S::select(m, a.y, b.y),
        z: S::select(m, a.z, b.z),
    }
}

/// The arrays as lanes.
#[inline(always)]
pub(super) fn load3<S: Simd>(s: S, v: &V8) -> L3<S::F> {
    L3 {
        x: s.load(&v.x),
        y: s.load(&v.y),
        z: s.load(&v.z),
    }
}

/// The lanes as arrays.
#[inline(always)]
pub(super) fn store3<S: Simd>(v: &L3<S::F>) -> V8 {
    V8 {
        x: S::store(v.x),
        y: S::store(v.y),
        z: S::store(v.z),
    }
}
