//! The nearest hit so far of each lane's ray, as a scan over the objects
//! keeps it ([`Nearest`]: a hit taken only where nearer, so the first of
//! equally near ones, as `Prepared::closest_among`), and what the scan found
//! ([`Found`]), which the shading takes on without testing the object again.

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::hits::hit_part;
use super::vec::{F8, L3};
use crate::geometry::Geom;
use crate::simd::Simd;

/// The nearest hits of a level's lanes: the lanes that meet nothing (bits),
/// the object each other lane meets (its index as `f32`), and where the scan
/// over the lanes found them, where (`t`) and on which part of it
/// (`hits::hit_part`): the shading then need not test it again.
#[derive(Clone, Copy)]
pub(super) struct Found<F> {
    pub(super) missed: u8,
    pub(super) which: F,
    pub(super) at: Option<(F, F)>,
}

impl<F: Copy> Found<F> {
    /// The lanes as arrays, to cross a call.
    #[inline(always)]
    pub(super) fn store<S: Simd<F = F>>(&self) -> Found<F8> {
        Found {
            missed: self.missed,
            which: S::store(self.which),
            at: self.at.map(|(t, part)| (S::store(t), S::store(part))),
        }
    }
}

impl Found<F8> {
    /// The arrays back as lanes.
    #[inline(always)]
    pub(super) fn load<S: Simd>(&self, s: S) -> Found<S::F> {
        Found {
            missed: self.missed,
            which: s.load(&self.which),
            at: self.at.map(|(t, part)| (s.load(&t), s.load(&part))),
        }
    }
}

/// A scan's nearest hit so far per lane: where, the object (its index as
/// `f32`) and the part of it (`hits::hit_part`; 0 for a plane), which change
/// together.
#[derive(Clone, Copy)]
pub(super) struct Nearest<F> {
    pub(super) best: F,
    which: F,
    part: F,
}

impl<F: Copy> Nearest<F> {
    /// Nothing met before `limit` yet.
    #[inline(always)]
    pub(super) fn before<S: Simd<F = F>>(s: S, limit: F) -> Self {
        Self {
            best: limit,
            which: s.splat(0.0),
            part: s.splat(0.0),
        }
    }

    /// Object `k`, met at `t` on part `part`, where nearer than the nearest so
    /// far in the lanes of `offered`.
    #[inline(always)]
    pub(super) fn offer<S: Simd<F = F>>(
        &mut self,
        s: S,
        offered: S::M,
        (t, part): (F, F),
        k: usize,
    ) {
        let take = offered & S::lt(t, self.best);
        self.best = S::select(take, t, self.best);
        self.which = S::select(take, s.splat(k as f32), self.which);
        self.part = S::select(take, part, self.part);
    }

    /// Bounded object `k` (`g`), tested by its hit test in the lanes of
    /// `inside` (those within its box; the test need be right only there),
    /// offered where nearer ([`Self::offer`]).
    #[inline(always)]
    pub(super) fn offer_object<S: Simd<F = F>>(
        &mut self,
        s: S,
        inside: S::M,
        (g, k): (&Geom, usize),
        (o, d): (&L3<F>, &L3<F>),
    ) {
        let hit = hit_part(s, g, (o, d), S::bits(inside));
        self.offer(s, inside, hit, k);
    }

    /// As [`Found`], the lanes of `missed` meeting nothing.
    #[inline(always)]
    pub(super) fn found(self, missed: u8) -> Found<F> {
        Found {
            missed,
            which: self.which,
            at: Some((self.best, self.part)),
        }
    }
}
