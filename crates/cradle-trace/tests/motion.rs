//! The motion filter of incremental frames never drops a ray segment that meets
//! a moved object: `Near::meets`, and `NearSet::meets` over both shapes (in the
//! AVX2 build and the portable one), say yes for every segment that comes within
//! a ball or a string, found independently by sampling in f64; and the one it
//! leaves out, a segment well through a moved ball where it was and is, truly
//! passes through both.

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

/// A moved ball where it was (`c0`) and where it is (`c1`), radius 0.02 m, with
/// one cell, and the set that leaves out segments through both.
fn moved_ball(c0: Vec3, c1: Vec3) -> NearSet {
    let ball = |centre| Shape::Sphere {
        centre,
        radius: 0.02,
    };
    let nears = [c0, c1].map(|c| (1, Near::of(&ball(c)).unwrap()));
    NearSet::new(nears.to_vec()).with_balls(vec![(c0, 0.02)], vec![(c1, 0.02)])
}

#[test]
fn a_segment_through_a_moved_ball_where_it_was_and_where_it_is_is_left_out() {
    let (c0, c1) = (Vec3::ZERO, Vec3::new(0.005, 0.0, 0.0));
    let set = moved_ball(c0, c1);
    let seg = |a: [f32; 3], b: [f32; 3]| Seg {
        a: Vec3::from(a),
        b: Vec3::from(b),
    };
    for portable in [false, true] {
        force_portable(portable);
        // Through both, 1 mm from the centres: a shadow ray blocked before and after.
        assert!(!set.meets(&seg([-0.1, 0.001, 0.0], [0.1, 0.001, 0.0]), 1));
        // Ending inside both, or on the surface where the ball was (a ray
        // that ends at its nearest hit): taken.
        assert!(set.meets(&seg([-0.1, 0.001, 0.0], [0.0, 0.001, 0.0]), 1));
        assert!(set.meets(&seg([-0.1, 0.0, 0.0], [-0.02, 0.0, 0.0]), 1));
        // Starting on the surface where the ball is (a shadow ray from the
        // ball itself would) and passing through where it was: taken.
        assert!(set.meets(&seg([0.025, 0.0, 0.0], [-0.1, 0.0, 0.0]), 1));
        // Within 0.05 mm of both surfaces, less than the pad deep: taken.
        assert!(set.meets(&seg([-0.1, 0.01995, 0.0], [0.1, 0.01995, 0.0]), 1));
        // Through where it was, past where it is: taken.
        let far = moved_ball(c0, Vec3::new(0.0, 0.1, 0.0));
        assert!(far.meets(&seg([-0.1, 0.001, 0.0], [0.1, 0.001, 0.0]), 1));
    }
    force_portable(false);
}

#[test]
fn a_segment_left_out_passes_well_through_the_ball_where_it_was_and_is() {
    let mut rng = Lcg(7);
    let (c0, c1) = (Vec3::new(0.0, 0.01, 0.0), Vec3::new(0.012, 0.0, 0.004));
    let set = moved_ball(c0, c1);
    let mut left_out = 0;
    for i in 0..20_000 {
        let (p, q) = (rng.point(), rng.point());
        let s = Seg { a: p, b: q };
        let (pd, qd) = (p.as_dvec3(), q.as_dvec3());
        for portable in [false, true] {
            force_portable(portable);
            if set.meets(&s, 1) {
                continue;
            }
            // Left out: a segment that comes within either ball must pass
            // through both (in f64), entering and leaving each.
            for c in [c0, c1].map(Vec3::as_dvec3) {
                let within = to_segment(c, pd, qd) <= 0.02;
                let through =
                    to_segment(c, pd, qd) < 0.02 && pd.distance(c) > 0.02 && qd.distance(c) > 0.02;
                assert!(!within || through, "segment {i} left out, not through");
                if through {
                    left_out += usize::from(portable);
                }
            }
        }
    }
    force_portable(false);
    // Some segments were left out (each counted per ball, portable build).
    assert!(left_out > 100, "{left_out} left out");
}

#[test]
fn a_moved_object_tested_as_one_shape_around_both_finds_what_its_two_shapes_find() {
    let mut rng = Lcg(11);
    let mut taken = 0;
    // Moves from a hundredth of a millimetre to 9 cm: the string's shapes
    // stay two from 4 mm on, the ball's at 9 cm (each over twice its grown
    // radius: 1.4 mm and 4.02 cm).
    for (i, step) in [1e-5_f32, 1e-3, 4e-3, 3e-2, 9e-2]
        .into_iter()
        .cycle()
        .take(40)
        .enumerate()
    {
        let dir = (rng.point() * 5.0).normalize_or(Vec3::X);
        let c0 = rng.point() * 0.25;
        let c1 = c0 + dir * step;
        let pivot = c0 + Vec3::new(0.03, 0.16, 0.05);
        let ball = |centre| Shape::Sphere {
            centre,
            radius: 0.02,
        };
        let string = |end| Shape::Cylinder {
            a: pivot,
            b: end,
            radius: 0.0006,
        };
        let shapes = [ball(c0), ball(c1), string(c0), string(c1)];
        // Each shape with its own cell; a segment's cells are drawn at random.
        let nears: Vec<_> = shapes
            .iter()
            .zip([1, 2, 4, 8])
            .map(|(s, cell)| (cell, Near::of(s).unwrap()))
            .collect();
        let one_by_one = NearSet::new(nears.clone());
        let paired = NearSet::moved(vec![[nears[0], nears[1]], [nears[2], nears[3]]]);
        for j in 0..500 {
            // Most segments aimed near the ball or the string.
            let p = c0 + rng.point() * 0.5;
            let aim = if j % 2 == 0 {
                c1
            } else {
                pivot.lerp(c0, rng.next())
            };
            let q = p + (aim + rng.point() * 0.05 - p) * (0.5 + rng.next());
            let s = Seg { a: p, b: q };
            let cells = 1 + (rng.next() * 15.0) as u128;
            for portable in [false, true] {
                force_portable(portable);
                let want = one_by_one.meets(&s, cells);
                assert_eq!(paired.meets(&s, cells), want, "move {i}, segment {j}");
                taken += usize::from(want);
            }
        }
    }
    force_portable(false);
    assert!(taken > 2000, "{taken} segments met a shape");
}
