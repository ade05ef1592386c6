//! Shadow culling's data for a frame's [`Prepared`] scene: per plane and light
//! the footprints of the objects' shadows, and per object the objects that can
//! block its shadow rays, built side by side.

use super::Prepared;
use crate::bvh::Bvh;
use crate::casters::{Casters, piece_boxes};
use crate::geometry::Aabb;
use crate::scene::Shape;
use crate::shadow::Footprints;
use rayon::prelude::*;

impl Prepared<'_> {
    /// Turns shadow culling ([`Footprints`]) on or off (off: every shadow ray
    /// tests every object, the reference).
    #[must_use]
    pub fn with_shadow_culling(mut self, on: bool) -> Self {
        if !on {
            (self.footprints, self.casters) = (None, None);
            return self;
        }
        // The footprints and the casters are independent: built side by side.
        let this = &self;
        let (footprints, casters) = rayon::join(|| this.footprints_of(), || this.casters_of());
        (self.footprints, self.casters) = (Some(footprints), Some(casters));
        self
    }

    /// Per plane, per light, the footprints of the bounded objects.
    fn footprints_of(&self) -> Vec<Vec<Option<Footprints>>> {
        let scene = self.scene;
        self.planes
            .iter()
            .map(|&i| {
                let Shape::Plane { point, normal } = scene.objects[i].shape else {
                    unreachable!("only planes are unbounded")
                };
                scene
                    .lights
                    .iter()
                    .map(|l| {
                        let pieces = |i: usize| piece_boxes(&scene.objects[i].shape);
                        Footprints::new(point, normal, l, &self.bounded, pieces)
                    })
                    .collect()
            })
            .collect()
    }

    /// Per object, the objects that can block its shadow rays.
    fn casters_of(&self) -> Vec<Option<Casters>> {
        let scene = self.scene;
        // Beyond a few dozen objects, find each piece's casters through a
        // hierarchy rather than by testing every object.
        let boxes: Vec<Aabb> = self.bounded.iter().map(|&(_, b)| b).collect();
        let bvh = (boxes.len() > 32).then(|| Bvh::new(&boxes));
        // (Object by object over the pool: each takes a list per light and
        // piece, and a frame waits for them before it traces.)
        scene
            .objects
            .par_iter()
            .enumerate()
            .map(|(i, o)| {
                let bvh = bvh.as_ref().map(|b| (b, &boxes[..]));
                Casters::new((i, &o.shape), &scene.lights, &self.bounded, bvh)
            })
            .collect()
    }
}
