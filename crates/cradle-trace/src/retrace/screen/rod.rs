//! The screen region of a string or rod piece under each of the screen
//! filter's maps (`super::Map`): a rectangle along the image of its axis, and
//! per row where that quad crosses the row's band.

use super::{Map, PAD_PX, Region, apply};
use crate::camera::CameraRays;
use glam::Vec3;

/// The region of the rod from `a` to `b` of radius `g` under `m`: the box
/// around it (along its axis, and `g` either side across, which holds the
/// capsule) has 8 corners whose images bound its image; on the screen they
/// lie in a rectangle along the image of the axis (a straight line: every map
/// keeps lines straight), padded by [`PAD_PX`]; where a corner's image lies
/// behind the eye, the box of the hull's image in front
/// ([`CameraRays::hull_box`]). `None` where a corner's image is unbounded.
pub(super) fn rod_region(
    cam: &CameraRays,
    (a, b, g): (Vec3, Vec3, f32),
    m: &Map,
) -> Option<Region> {
    // (A piece of no length: any axis; the box then holds the ball around it.)
    let w = (b - a).try_normalize().unwrap_or(Vec3::X);
    let (e1, e2) = w.any_orthonormal_pair();
    let (a, b) = (a - w * g, b + w * g);
    let mut images = [Vec3::ZERO; 8];
    for (i, image) in images.iter_mut().enumerate() {
        let end = if i & 1 == 0 { a } else { b };
        let s1 = if i & 2 == 0 { -g } else { g };
        let s2 = if i & 4 == 0 { -g } else { g };
        *image = apply(m, end + e1 * s1 + e2 * s2)?;
    }
    let mut q = [(0.0f32, 0.0f32); 8];
    for (q, &image) in q.iter_mut().zip(&images) {
        match cam.project(image) {
            Some(p) if p.0.is_finite() && p.1.is_finite() => *q = p,
            // Reaching behind the eye: the box of what lies in front.
            _ => return Some(Region::Box(cam.hull_box(&images))),
        }
    }
    // The axis on the screen: through the images of its ends.
    let (o, e) = (cam.project(apply(m, a)?)?, cam.project(apply(m, b)?)?);
    let (dx, dy) = (e.0 - o.0, e.1 - o.1);
    let len = (dx * dx + dy * dy).sqrt();
    if len.is_nan() || len <= 1e-3 {
        let (lo, hi) = q
            .iter()
            .fold(((f32::MAX, f32::MAX), (f32::MIN, f32::MIN)), |(l, h), p| {
                ((l.0.min(p.0), l.1.min(p.1)), (h.0.max(p.0), h.1.max(p.1)))
            });
        return Some(Region::Box([[lo.0, hi.0], [lo.1, hi.1]]));
    }
    let (u, v) = ((dx / len, dy / len), (-dy / len, dx / len));
    let at = |p: &(f32, f32), d: (f32, f32)| (p.0 - o.0) * d.0 + (p.1 - o.1) * d.1;
    let span = |d| {
        q.iter().fold((f32::MAX, f32::MIN), |(l, h), p| {
            (l.min(at(p, d)), h.max(at(p, d)))
        })
    };
    let ((t0, t1), (s0, s1)) = (span(u), span(v));
    let (t0, t1, s0, s1) = (t0 - PAD_PX, t1 + PAD_PX, s0 - PAD_PX, s1 + PAD_PX);
    let corner = |t: f32, s: f32| (o.0 + u.0 * t + v.0 * s, o.1 + u.1 * t + v.1 * s);
    Some(Region::Quad([
        corner(t0, s0),
        corner(t1, s0),
        corner(t1, s1),
        corner(t0, s1),
    ]))
}

/// The least and greatest x of the convex quad `q` within the band of rows
/// from `y0` to `y1`: among its corners in the band and where its sides cross
/// the band's edges. `None` where it misses the band.
pub(super) fn band_x(q: &[(f32, f32); 4], (y0, y1): (f32, f32)) -> Option<(f32, f32)> {
    let (mut lo, mut hi) = (f32::MAX, f32::MIN);
    for i in 0..4 {
        let (p, r) = (q[i], q[(i + 1) % 4]);
        if (y0..=y1).contains(&p.1) {
            (lo, hi) = (lo.min(p.0), hi.max(p.0));
        }
        for y in [y0, y1] {
            if (p.1 - y) * (r.1 - y) < 0.0 {
                let x = p.0 + (r.0 - p.0) * ((y - p.1) / (r.1 - p.1));
                (lo, hi) = (lo.min(x), hi.max(x));
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}
