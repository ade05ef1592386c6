//! A frame's scene made ready to trace: world-space bounds per object, one box
//! around everything but the planes, and the queries the shading needs (nearest
//! hit, any hit).

use super::geometry::{Aabb, Ray, hit_cylinder, hit_plane, hit_sphere};
use super::scene::{Object, Scene, Shape};
use glam::Vec3;

/// What a ray hit.
#[derive(Debug, Clone, Copy)]
pub struct Hit {
    /// Distance along the ray.
    pub t: f32,
    /// Index of the object in the scene.
    pub object: usize,
    /// Unit normal, turned to face the ray.
    pub normal: Vec3,
}

/// Bounds of a shape; `None` for unbounded planes.
fn bounds(shape: &Shape) -> Option<Aabb> {
    match *shape {
        Shape::Sphere { centre, radius } => Some(Aabb {
            min: centre - radius,
            max: centre + radius,
        }),
        Shape::Cylinder { a, b, radius } => {
            // The caps are discs of this radius; their extent along each world axis
            // is radius * sqrt(1 - u_i^2).
            let u = (b - a).normalize();
            let ext = radius * (Vec3::ONE - u * u).max(Vec3::ZERO).sqrt();
            Some(Aabb {
                min: a.min(b) - ext,
                max: a.max(b) + ext,
            })
        }
        Shape::Plane { .. } => None,
    }
}

/// The scene with its acceleration data.
#[derive(Debug, Clone)]
pub struct Prepared<'a> {
    /// The flat scene.
    pub scene: &'a Scene,
    bounded: Vec<(usize, Aabb)>,
    group: Aabb,
    planes: Vec<usize>,
}

impl<'a> Prepared<'a> {
    /// Bounds for every object of `scene`.
    #[must_use]
    pub fn new(scene: &'a Scene) -> Self {
        let mut bounded = Vec::new();
        let mut planes = Vec::new();
        let mut group = Aabb::EMPTY;
        for (i, o) in scene.objects.iter().enumerate() {
            match bounds(&o.shape) {
                Some(b) => {
                    group = group.union(b);
                    bounded.push((i, b));
                }
                None => planes.push(i),
            }
        }
        Self {
            scene,
            bounded,
            group,
            planes,
        }
    }

    /// Distance and outward normal of the ray's hit on object `i`, if any.
    fn hit_object(o: &Object, ray: &Ray) -> Option<(f32, Vec3)> {
        match o.shape {
            Shape::Sphere { centre, radius } => {
                hit_sphere(ray, centre, radius).map(|t| (t, (ray.at(t) - centre) / radius))
            }
            Shape::Cylinder { a, b, radius } => hit_cylinder(ray, a, b, radius),
            Shape::Plane { point, normal } => hit_plane(ray, point, normal).map(|t| (t, normal)),
        }
    }

    /// Every object in the order hit queries consider them (planes first, then the
    /// bounded ones), with its bounds (`None` for planes), so that ties in distance
    /// always resolve the same way.
    pub fn in_query_order(&self) -> impl Iterator<Item = (usize, Option<Aabb>)> + '_ {
        self.planes
            .iter()
            .map(|&i| (i, None))
            .chain(self.bounded.iter().map(|&(i, b)| (i, Some(b))))
    }

    /// The nearest hit before `t_max` among `candidates` (indices in query order),
    /// which must include every object the ray can hit: primary rays of a tile.
    #[must_use]
    pub fn closest_among(&self, ray: &Ray, t_max: f32, candidates: &[usize]) -> Option<Hit> {
        let mut best: Option<(f32, usize, Vec3)> = None;
        for &i in candidates {
            let limit = best.map_or(t_max, |b| b.0);
            if let Some((t, n)) = Self::hit_object(&self.scene.objects[i], ray)
                && t < limit
            {
                best = Some((t, i, n));
            }
        }
        best.map(|(t, object, n)| Hit {
            t,
            object,
            normal: if n.dot(ray.dir) > 0.0 { -n } else { n },
        })
    }

    /// The nearest hit before `t_max`.
    #[must_use]
    pub fn closest(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let mut best: Option<(f32, usize, Vec3)> = None;
        let consider = |i: usize, best: &mut Option<(f32, usize, Vec3)>| {
            let limit = best.map_or(t_max, |b| b.0);
            if let Some((t, n)) = Self::hit_object(&self.scene.objects[i], ray)
                && t < limit
            {
                *best = Some((t, i, n));
            }
        };
        for &i in &self.planes {
            consider(i, &mut best);
        }
        let inv = ray.dir.recip();
        if self.group.hit(ray, inv, t_max) {
            for &(i, ref b) in &self.bounded {
                if b.hit(ray, inv, best.map_or(t_max, |x| x.0)) {
                    consider(i, &mut best);
                }
            }
        }
        best.map(|(t, object, n)| Hit {
            t,
            object,
            normal: if n.dot(ray.dir) > 0.0 { -n } else { n },
        })
    }

    /// Whether anything lies on the ray before `t_max` (shadow rays: any hit ends them).
    #[must_use]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let blocks = |i: usize| {
            Self::hit_object(&self.scene.objects[i], ray).is_some_and(|(t, _)| t < t_max)
        };
        if self.planes.iter().any(|&i| blocks(i)) {
            return true;
        }
        let inv = ray.dir.recip();
        self.group.hit(ray, inv, t_max)
            && self
                .bounded
                .iter()
                .any(|&(i, ref b)| b.hit(ray, inv, t_max) && blocks(i))
    }
}
