//! The motion filter of incremental frames never drops a ray segment that meets
//! a moved object: `Near::meets`, and `NearSet::meets` over both shapes (in the
//! AVX2 build and the portable one), say yes for every segment that comes within
//! a ball or a string, found independently by sampling in f64.

use cradle_trace::motion::{Near, NearSet, Seg};
use cradle_trace::packet::force_portable;
use cradle_trace::scene::Shape;
use glam::{DVec3, Vec3};

/// A small deterministic generator (no dependency): uniform in 0..1.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 40) as f32) / (1u64 << 24) as f32
    }
    /// A point in the 0.4 m cube around the origin.
    fn point(&mut self) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next()) * 0.4 - 0.2
    }
}

/// Distance from `c` to segment `p`..`q` in f64: to the projection of `c`,
/// clamped to the segment.
fn to_segment(c: DVec3, p: DVec3, q: DVec3) -> f64 {
    let d = q - p;
    let t = ((c - p).dot(d) / d.length_squared().max(1e-300)).clamp(0.0, 1.0);
    (p + d * t).distance(c)
}

/// The least distance from 2,000 points along `p`..`q` to segment `a`..`b`: at
/// least the true distance of the two segments, so a value within a radius
/// means they truly come that close.
fn sampled(p: DVec3, q: DVec3, a: DVec3, b: DVec3) -> f64 {
    (0..=2000)
        .map(|k| to_segment(p + (q - p) * (f64::from(k) / 2000.0), a, b))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn no_segment_that_meets_a_ball_or_a_string_is_dropped() {
    let mut rng = Lcg(3);
    let ball = Shape::Sphere {
        centre: Vec3::new(0.01, -0.02, 0.0),
        radius: 0.02,
    };
    let (a, b) = (Vec3::new(-0.1, 0.15, 0.05), Vec3::new(0.02, -0.01, 0.0));
    let string = Shape::Cylinder {
        a,
        b,
        radius: 0.0006,
    };
    let (near_ball, near_string) = (Near::of(&ball).unwrap(), Near::of(&string).unwrap());
    // Each with a cell of its own: a segment that passed neither cell is let go.
    let set = NearSet::new(vec![(1, near_ball), (2, near_string)]);
    let (mut met, mut passed, mut set_passed) = (0, 0, 0);
    for i in 0..10_000 {
        // Half the segments aimed through the shapes' neighbourhood.
        let p = rng.point();
        let q = if i % 2 == 0 {
            let aim = a.lerp(b, rng.next()) + (rng.point() * 0.01);
            p + (aim - p) * (1.0 + rng.next())
        } else {
            rng.point()
        };
        let s = Seg { a: p, b: q };
        let (pd, qd) = (p.as_dvec3(), q.as_dvec3());
        // The set, in both builds (they may differ only where a shape's own
        // test is on its edge).
        let in_set: Vec<bool> = [false, true]
            .into_iter()
            .map(|portable| {
                force_portable(portable);
                let m = set.meets(&s, 3);
                assert!(!set.meets(&s, 4), "segment {i}: no cell in common");
                m
            })
            .collect();
        force_portable(false);
        // The ball: the distance from its centre.
        if to_segment(DVec3::new(0.01, -0.02, 0.0), pd, qd) <= 0.02 {
            met += 1;
            assert!(near_ball.meets(&s), "segment {i} meets the ball");
            assert!(in_set[0] && in_set[1], "segment {i} meets the ball: set");
            assert!(set.meets(&s, 1), "segment {i}: the ball's cell");
        }
        // The string: the least distance of the segment's samples to its axis.
        let (sa, sb) = (a.as_dvec3(), b.as_dvec3());
        let to_axis = sampled(pd, qd, sa, sb);
        if to_axis <= 0.0006 {
            met += 1;
            assert!(near_string.meets(&s), "segment {i} meets the string");
            assert!(in_set[0] && in_set[1], "segment {i} meets the string: set");
        } else if to_axis > 0.01 && !near_string.meets(&s) {
            passed += 1;
        }
        if !in_set[0] && !in_set[1] {
            set_passed += 1;
        }
    }
    // Both kinds were tried, and the filter does filter.
    assert!(met > 500, "{met} segments met a shape");
    assert!(
        passed > 2500,
        "{passed} segments far from the string passed"
    );
    assert!(set_passed > 2500, "{set_passed} segments passed the set");
}
