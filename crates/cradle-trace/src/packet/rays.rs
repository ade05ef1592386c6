//! The packet's rays between bounces: where each lane's ray starts and goes
//! ([`Bounce`], and as arrays [`Bounce8`] to cross a call), the plane it
//! leaves, the floor the eye's rays meet ([`Floor`]) and what a group of lanes
//! met ([`Met`]). Below the scene's queries (`scan`), the lights (`lights`)
//! and the bounces that drive both (`bounce`).

#![expect(
    clippy::inline_always,
    reason = "the lane code is inlined into each entry point, so the AVX2 one compiles it for AVX2"
)]

use super::vec::{F8, L3, V8};
use crate::camera::CameraRays;
use crate::prepared::Prepared;
use crate::scene::{Material, Shape};
use crate::simd::Simd;
use glam::Vec3;

/// The lanes' rays: from `origin` along `d`, bounce `depth`, path weight
/// `weight` per lane (the eye's rays: 0 and 1).
#[derive(Clone, Copy)]
pub(super) struct Bounce<F> {
    pub(super) origin: L3<F>,
    pub(super) d: L3<F>,
    pub(super) depth: u32,
    pub(super) weight: F,
    /// The lanes whose rays are free (`Record::segment`'s `free`): mirror rays of camera
    /// rays that met a plane (camera rays, at depth 0, are free in every lane).
    pub(super) free: u8,
    /// Per lane, the plane the ray leaves (its index as `f32`), which it does
    /// not test (`Prepared::closest_from`), or -1.
    pub(super) from: F,
}

/// [`Bounce`] as arrays, to pass to a function of its own.
pub(super) struct Bounce8 {
    pub(super) origin: V8,
    pub(super) d: V8,
    pub(super) depth: u32,
    pub(super) weight: F8,
    pub(super) free: u8,
    pub(super) from: F8,
}

/// The floor plane a packet shades: its object, point, normal and material.
#[derive(Clone, Copy)]
pub(crate) struct Floor<'a> {
    pub(super) object: usize,
    pub(super) normal: Vec3,
    pub(super) material: &'a Material,
    /// `(point - eye).dot(normal)`: the numerator of every primary ray's hit.
    pub(super) num: f32,
}

impl<'a> Floor<'a> {
    /// Plane `object` (the only thing a packet's rays can hit).
    pub(crate) fn of(p: &'a Prepared<'_>, cam: &CameraRays, object: usize) -> Option<Self> {
        let o = &p.scene.objects[object];
        let Shape::Plane { point, normal } = o.shape else {
            return None;
        };
        Some(Self {
            object,
            normal,
            material: &o.material,
            // hit_plane: (point - ray.origin).dot(normal), the eye for every lane.
            num: (point - cam.origin).dot(normal),
        })
    }
}

/// What the lanes to shade met: the packet's floor seen from the eye (depth
/// 0), or object `object` at any depth (a
/// plane or not), met from outside in the lanes of `outside`.
#[derive(Clone, Copy)]
pub(super) enum Met<'m> {
    Floor(&'m Floor<'m>),
    Object {
        object: usize,
        material: &'m Material,
        outside: u8,
        plane: bool,
    },
}

impl Met<'_> {
    /// The object met.
    #[inline(always)]
    pub(super) fn object(&self) -> usize {
        match *self {
            Met::Floor(f) => f.object,
            Met::Object { object, .. } => object,
        }
    }

    #[inline(always)]
    pub(super) fn material(&self) -> &Material {
        match *self {
            Met::Floor(f) => f.material,
            Met::Object { material, .. } => material,
        }
    }
}

/// The plane lane `i`'s ray leaves (`Bounce::from`), as
/// `Prepared::closest_from` takes it: a plane's own rays do not test it.
#[inline(always)]
pub(super) fn leaving<S: Simd>(from: S::F, i: usize) -> Option<(usize, bool)> {
    let f = S::store(from)[i];
    (f >= 0.0).then_some((f as usize, false))
}
