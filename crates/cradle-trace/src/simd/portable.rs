//! The portable lane build: eight-element arrays and plain loops, which the
//! compiler vectorizes as the target allows (SSE2 on x86-64). The fallback of
//! the AVX2 build, and the one other targets run.

#![expect(
    clippy::inline_always,
    reason = "each operation is a loop that must inline into its kernel"
)]

use super::{Kernel, Simd};
use crate::color::rgba8_lanes;
use crate::geometry::floor_i64;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// The portable token.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Portable;

/// Eight floats.
#[derive(Clone, Copy, Debug)]
pub(crate) struct P8([f32; 8]);

/// Eight conditions as bits.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bits(u8);

#[inline(always)]
fn map(a: P8, f: impl Fn(f32) -> f32) -> P8 {
    let mut out = a.0;
    for o in &mut out {
        *o = f(*o);
    }
    P8(out)
}

#[inline(always)]
fn zip(a: P8, b: P8, f: impl Fn(f32, f32) -> f32) -> P8 {
    let mut out = a.0;
    for (o, b) in out.iter_mut().zip(b.0) {
        *o = f(*o, b);
    }
    P8(out)
}

#[inline(always)]
fn test(a: P8, b: P8, f: impl Fn(f32, f32) -> bool) -> Bits {
    let mut m = 0;
    for (i, (a, b)) in a.0.into_iter().zip(b.0).enumerate() {
        m |= u8::from(f(a, b)) << i;
    }
    Bits(m)
}

macro_rules! binary {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for P8 {
            type Output = P8;
            #[inline(always)]
            fn $f(self, b: P8) -> P8 {
                zip(self, b, |a, b| a $op b)
            }
        }
    };
}
binary!(Add, add, +);
binary!(Sub, sub, -);
binary!(Mul, mul, *);
binary!(Div, div, /);

impl Neg for P8 {
    type Output = P8;
    #[inline(always)]
    fn neg(self) -> P8 {
        map(self, |a| -a)
    }
}

impl BitAnd for Bits {
    type Output = Bits;
    #[inline(always)]
    fn bitand(self, b: Bits) -> Bits {
        Bits(self.0 & b.0)
    }
}

impl BitOr for Bits {
    type Output = Bits;
    #[inline(always)]
    fn bitor(self, b: Bits) -> Bits {
        Bits(self.0 | b.0)
    }
}

impl Not for Bits {
    type Output = Bits;
    #[inline(always)]
    fn not(self) -> Bits {
        Bits(!self.0)
    }
}

impl Simd for Portable {
    type F = P8;
    type M = Bits;

    #[inline(always)]
    fn splat(self, v: f32) -> P8 {
        P8([v; 8])
    }
    #[inline(always)]
    fn load(self, v: &[f32; 8]) -> P8 {
        P8(*v)
    }
    #[inline(always)]
    fn mask(self, bits: u8) -> Bits {
        Bits(bits)
    }
    #[inline(always)]
    fn store(v: P8) -> [f32; 8] {
        v.0
    }
    #[inline(always)]
    fn bits(m: Bits) -> u8 {
        m.0
    }
    #[inline(always)]
    fn sqrt(v: P8) -> P8 {
        map(v, f32::sqrt)
    }
    #[inline(always)]
    fn abs(v: P8) -> P8 {
        map(v, f32::abs)
    }
    #[inline(always)]
    fn min(a: P8, b: P8) -> P8 {
        zip(a, b, |a, b| if a < b { a } else { b })
    }
    #[inline(always)]
    fn max(a: P8, b: P8) -> P8 {
        zip(a, b, |a, b| if a > b { a } else { b })
    }
    #[inline(always)]
    fn trunc(v: P8) -> [i32; 8] {
        let mut out = [0; 8];
        for (o, v) in out.iter_mut().zip(v.0) {
            *o = v as i32;
        }
        out
    }
    #[inline(always)]
    fn floor_small(v: P8) -> P8 {
        // Exact below 2^22, where every value converts to i64 and back exactly
        // (no libm call: the portable build has no rounding instruction).
        map(v, |a| floor_i64(a) as f32)
    }
    #[inline(always)]
    fn lt(a: P8, b: P8) -> Bits {
        test(a, b, |a, b| a < b)
    }
    #[inline(always)]
    fn le(a: P8, b: P8) -> Bits {
        test(a, b, |a, b| a <= b)
    }
    #[inline(always)]
    fn rgba8(self, r: &[f32; 8], g: &[f32; 8], b: &[f32; 8]) -> [u32; 8] {
        rgba8_lanes(*r, *g, *b)
    }
    #[inline(always)]
    fn enter<K: Kernel>(self, k: K) -> K::Output {
        k.run(self)
    }
    #[inline(always)]
    fn prefetch<T>(self, _: *const T) {}
    #[inline(always)]
    fn meeting(self, v: &[u128; 8], with: u128) -> u8 {
        (v.iter().enumerate()).fold(0, |m, (i, &c)| m | u8::from(c & with != 0) << i)
    }
    #[inline(always)]
    fn select(m: Bits, a: P8, b: P8) -> P8 {
        let mut out = b.0;
        for (i, (o, a)) in out.iter_mut().zip(a.0).enumerate() {
            if m.0 >> i & 1 != 0 {
                *o = a;
            }
        }
        P8(out)
    }
}
