//! Rays and their intersections with the three shapes: sphere, finite capped
//! cylinder of any axis, plane; a shape's bounds and its hit test made ready
//! ([`Geom`]), and what a ray hit ([`Hit`]). Nearest hit beyond `T_MIN` only.

use super::scene::Shape;
use glam::Vec3;

/// Hits closer than this (m) are ignored: secondary rays start on a surface.
pub const T_MIN: f32 = 1e-5;

/// Secondary rays start this far (m) off the surface, along its normal.
pub(crate) const SURFACE_OFFSET: f32 = 2e-5;

/// A ray with a unit direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Start point.
    pub origin: Vec3,
    /// Unit direction.
    pub dir: Vec3,
}

impl Ray {
    /// The point at distance `t`.
    #[must_use]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// Nearest `t > T_MIN` where the ray meets the sphere (from outside or inside).
///
/// The discriminant is `r^2 - |f|^2`, with `f` the offset of the ray's nearest
/// point from the centre, not `b^2 - (|oc|^2 - r^2)`: seen from 10 m the latter
/// subtracts two numbers near 100 and keeps an error near 1e-5, a fifth of a
/// 2 cm ball's `r^2`, which shows as rings of wrong depth and speckled shadows.
#[must_use]
pub fn hit_sphere(ray: &Ray, centre: Vec3, radius: f32) -> Option<f32> {
    let oc = ray.origin - centre;
    let b = oc.dot(ray.dir);
    let f = oc - ray.dir * b;
    let disc = radius * radius - f.length_squared();
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    [-b - s, -b + s].into_iter().find(|&t| t > T_MIN)
}

/// Nearest `t > T_MIN` and the outward normal where the ray meets the cylinder
/// from `a` to `b` with flat caps.
#[must_use]
pub fn hit_cylinder(ray: &Ray, a: Vec3, b: Vec3, radius: f32) -> Option<(f32, Vec3)> {
    Cylinder::new(a, b, radius).hit(ray)
}

/// A capped cylinder with its axis worked out once per frame, not once per ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    a: Vec3,
    b: Vec3,
    /// Unit axis from `a` to `b`.
    u: Vec3,
    len: f32,
    radius: f32,
}

impl Cylinder {
    /// Whether `p` lies farther than `margin` outside the cylinder (beyond a cap,
    /// or off the axis by more than the radius).
    #[must_use]
    pub fn clear_of(&self, p: Vec3, margin: f32) -> bool {
        let s = (p - self.a).dot(self.u);
        if s < -margin || s > self.len + margin {
            return true;
        }
        let off = p - self.a - self.u * s;
        off.length_squared() > (self.radius + margin) * (self.radius + margin)
    }

    /// The cylinder from `a` to `b`.
    #[must_use]
    pub fn new(a: Vec3, b: Vec3, radius: f32) -> Self {
        let axis = b - a;
        let len = axis.length();
        Self {
            a,
            b,
            u: axis / len,
            len,
            radius,
        }
    }

    /// Its ends `a` and `b`, unit axis, length and radius.
    pub(crate) fn parts(&self) -> (Vec3, Vec3, Vec3, f32, f32) {
        (self.a, self.b, self.u, self.len, self.radius)
    }

    /// Nearest `t > T_MIN` and the outward normal where the ray meets it.
    #[must_use]
    pub fn hit(&self, ray: &Ray) -> Option<(f32, Vec3)> {
        let Self {
            a,
            b,
            u,
            len,
            radius,
        } = *self;
        let ao = ray.origin - a;
        let (du, ou) = (ray.dir.dot(u), ao.dot(u));
        let d_perp = ray.dir - u * du;
        let o_perp = ao - u * ou;
        let qa = d_perp.length_squared();
        let qb = o_perp.dot(d_perp);
        // The nearest root so far and where it lies (0 the body, 1 and 2 the caps
        // at a and b); the normal is worked out once, for the one kept.
        let mut best: Option<(f32, u8)> = None;
        let nearer =
            |best: Option<(f32, u8)>, t: f32| t > T_MIN && best.is_none_or(|(bt, _)| t < bt);
        // Body: |o_perp + t d_perp| = r, within the axial extent. A ray parallel to the
        // axis (qa ~ 0) can only meet the caps.
        if qa > 1e-12 {
            // qb^2 - qa (|o_perp|^2 - r^2), written as qa (r^2 - |f|^2) with f the
            // nearest approach to the axis, for the precision `hit_sphere` keeps.
            let f = o_perp - d_perp * (qb / qa);
            let disc = qa * (radius * radius - f.length_squared());
            // Missing the infinite cylinder misses the caps too (discs inside it):
            // most rays that reach a thin string's box end here.
            if disc < 0.0 {
                return None;
            }
            let s = disc.sqrt();
            for t in [(-qb - s) / qa, (-qb + s) / qa] {
                let along = ou + t * du;
                if (0.0..=len).contains(&along) && nearer(best, t) {
                    best = Some((t, 0));
                }
            }
        }
        // Caps: the planes through a (facing -u) and b (facing +u), within the
        // radius; a cap no nearer than the hit so far is not looked at.
        if du.abs() > 1e-12 {
            for (part, end, along) in [(1, a, 0.0), (2, b, len)] {
                let t = (along - ou) / du;
                if nearer(best, t) && (ray.at(t) - end).length_squared() <= radius * radius {
                    best = Some((t, part));
                }
            }
        }
        best.map(|(t, part)| {
            let normal = match part {
                0 => (o_perp + d_perp * t).normalize(),
                1 => -u,
                _ => u,
            };
            (t, normal)
        })
    }
}

/// `t > T_MIN` where the ray meets the plane through `point` with unit `normal`.
#[must_use]
pub fn hit_plane(ray: &Ray, point: Vec3, normal: Vec3) -> Option<f32> {
    let denom = ray.dir.dot(normal);
    if denom.abs() < 1e-9 {
        return None;
    }
    let t = (point - ray.origin).dot(normal) / denom;
    (t > T_MIN).then_some(t)
}

/// An axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (grows from nothing).
    pub const EMPTY: Self = Self {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// The smallest box holding both.
    #[must_use]
    pub fn union(self, o: Self) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// Whether the two boxes share a point (faces touching count).
    #[must_use]
    pub fn overlaps(&self, o: &Self) -> bool {
        self.min.cmple(o.max).all() && o.min.cmple(self.max).all()
    }

    /// Its 8 corners: bit 0 of the index picks `max.x` over `min.x`, bit 1
    /// `max.y`, bit 2 `max.z`.
    #[must_use]
    pub fn corners(&self) -> [Vec3; 8] {
        std::array::from_fn(|i| {
            Vec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            )
        })
    }

    /// Whether the ray meets the box between `T_MIN` and `t_max` (slab test).
    #[must_use]
    pub fn hit(&self, ray: &Ray, inv_dir: Vec3, t_max: f32) -> bool {
        let t1 = (self.min - ray.origin) * inv_dir;
        let t2 = (self.max - ray.origin) * inv_dir;
        let near = t1.min(t2).max_element().max(T_MIN);
        let far = t1.max(t2).min_element().min(t_max);
        near <= far
    }
}

/// What a ray hit.
#[derive(Debug, Clone, Copy)]
pub struct Hit {
    /// Distance along the ray.
    pub t: f32,
    /// Index of the object in the scene.
    pub object: usize,
    /// Unit normal, turned to face the ray.
    pub normal: Vec3,
    /// Whether the ray met the surface from outside (the normal was not turned).
    pub outside: bool,
}

impl Hit {
    /// The hit at `t` on `object`, whose outward normal there is `n`.
    #[must_use]
    pub(crate) fn facing(ray: &Ray, t: f32, object: usize, n: Vec3) -> Self {
        let inside = n.dot(ray.dir) > 0.0;
        Self {
            t,
            object,
            normal: if inside { -n } else { n },
            outside: !inside,
        }
    }
}

/// Bounds of a shape; `None` for unbounded planes.
pub(crate) fn bounds(shape: &Shape) -> Option<Aabb> {
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

/// A shape with what its hit test needs worked out once per frame.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Geom {
    Sphere { centre: Vec3, radius: f32 },
    Cylinder(Cylinder),
    Plane { point: Vec3, normal: Vec3 },
}

impl Geom {
    pub(crate) fn new(shape: &Shape) -> Self {
        match *shape {
            Shape::Sphere { centre, radius } => Self::Sphere { centre, radius },
            Shape::Cylinder { a, b, radius } => Self::Cylinder(Cylinder::new(a, b, radius)),
            Shape::Plane { point, normal } => Self::Plane { point, normal },
        }
    }
}

/// `v.floor() as i64`, exactly (saturating, NaN to 0), without a call to libm's
/// `floorf` (the portable x86-64 build has no rounding instruction): truncate,
/// then step down where truncation went up.
#[inline]
#[must_use]
pub fn floor_i64(v: f32) -> i64 {
    let t = v as i64;
    if (t as f32) > v {
        t.saturating_sub(1)
    } else {
        t
    }
}
