//! Footprints of pieces: a slanted rod binned by its pieces' rectangles.

use super::Footprints;
use crate::casters::piece_boxes;
use crate::geometry::bounds;
use crate::geometry::{Aabb, Ray, hit_cylinder};
use crate::scene::{Light, Shape};
use glam::Vec3;

/// A slanted string and a post of the frame, objects 1 and 2.
fn rods() -> [(usize, Shape); 2] {
    [
        (
            1,
            Shape::Cylinder {
                a: Vec3::new(-0.1, 0.25, 0.03),
                b: Vec3::new(0.05, 0.05, -0.01),
                radius: 0.0006,
            },
        ),
        (
            2,
            Shape::Cylinder {
                a: Vec3::new(0.12, 0.0, 0.04),
                b: Vec3::new(0.12, 0.26, 0.04),
                radius: 0.004,
            },
        ),
    ]
}

/// Cells holding object `i`.
fn cells_of(fp: &Footprints, i: usize) -> usize {
    (0..fp.n.0 * fp.n.1)
        .filter(|&k| fp.cell(k).contains(&i))
        .count()
}

#[test]
fn every_floor_point_a_rod_shadows_finds_it_and_pieces_bin_it_in_fewer_cells() {
    let rods = rods();
    let bounded: Vec<(usize, Aabb)> = rods
        .iter()
        .map(|(i, s)| (*i, bounds(s).expect("bounded")))
        .collect();
    let shape = |i: usize| &rods.iter().find(|(j, _)| *j == i).expect("a rod").1;
    let light = Light::Point {
        position: Vec3::new(-0.5, 0.9, 0.7),
        color: Vec3::ONE,
    };
    let cut = Footprints::new(Vec3::ZERO, Vec3::Y, &light, &bounded, |i| {
        piece_boxes(shape(i))
    })
    .expect("lit");
    let whole =
        Footprints::new(Vec3::ZERO, Vec3::Y, &light, &bounded, |_| Vec::new()).expect("lit");
    // Both grids hold both rods; the pieces put each in fewer cells (here
    // the whole boxes' rectangles cover several times the rods' footprints).
    for (i, _) in &rods {
        let (c, w) = (cells_of(&cut, *i), cells_of(&whole, *i));
        assert!(c > 0 && c * 2 <= w, "rod {i}: {c} cells cut, {w} whole");
    }
    // Points of the floor around the shadows: wherever a shadow ray from
    // just above one meets a rod, the point's list holds that rod.
    let Light::Point { position, .. } = light else {
        unreachable!()
    };
    let mut met = 0;
    for gx in 0..400 {
        for gz in 0..400 {
            let start = Vec3::new(-0.2 + gx as f32 * 0.0015, 2e-5, -0.4 + gz as f32 * 0.0015);
            let to = position - start;
            let ray = Ray {
                origin: start,
                dir: to.normalize(),
            };
            let (list, always) = cut.candidates(start).expect("lit");
            for (i, s) in &rods {
                let Shape::Cylinder { a, b, radius } = *s else {
                    unreachable!()
                };
                if hit_cylinder(&ray, a, b, radius).is_some_and(|(t, _)| t < to.length()) {
                    met += 1;
                    assert!(
                        list.contains(i) || always.contains(i),
                        "rod {i} shadows {start} but its cell does not hold it"
                    );
                }
            }
        }
    }
    assert!(met > 500, "the grid of points meets the shadows ({met})");
}

/// A row of `n` balls, each on two slanted strings, ball `k` at `x[k]`, as
/// (object, shape): object 0 is the floor, so the row starts at 1.
fn row(x: &[f32]) -> Vec<(usize, Shape)> {
    let mut shapes = Vec::new();
    for (k, &x) in x.iter().enumerate() {
        let centre = Vec3::new(x, 0.05, 0.0);
        shapes.push((
            1 + 3 * k,
            Shape::Sphere {
                centre,
                radius: 0.02,
            },
        ));
        for (s, z) in [(2, -0.08), (3, 0.08)] {
            let a = Vec3::new(0.04 * (k as f32 - 4.5), 0.2, z);
            let shape = Shape::Cylinder {
                a,
                b: centre,
                radius: 0.0005,
            };
            shapes.push((s + 3 * k, shape));
        }
    }
    shapes
}

/// Each cell's objects, sorted, and the objects tested everywhere, sorted.
fn lists(fp: &Footprints) -> (Vec<Vec<usize>>, Vec<usize>) {
    let sorted = |s: &[usize]| {
        let mut v = s.to_vec();
        v.sort_unstable();
        v
    };
    let cells = (0..fp.n.0 * fp.n.1).map(|k| sorted(fp.cell(k))).collect();
    (cells, sorted(&fp.always))
}

#[test]
fn footprints_with_moved_objects_hold_in_each_cell_what_fresh_ones_hold() {
    let lights = [
        Light::Point {
            position: Vec3::new(0.7, 0.6, 0.5),
            color: Vec3::ONE,
        },
        Light::Point {
            position: Vec3::new(-0.3, 0.35, -0.4),
            color: Vec3::ONE,
        },
        Light::Directional {
            direction: Vec3::new(0.2, -1.0, 0.1).normalize(),
            color: Vec3::ONE,
        },
    ];
    let xs: Vec<f32> = (0..10).map(|k| 0.04 * (k as f32 - 4.5)).collect();
    let before = row(&xs);
    // Balls 4 and 5 swing a little (the row's ends stay, so the grid's bounds
    // do too); the query order reverses.
    let mut moved_xs = xs.clone();
    moved_xs[4] -= 0.011;
    moved_xs[5] += 0.007;
    let after = row(&moved_xs);
    let moved: Vec<usize> = (13..=18).collect();
    let boxed = |shapes: &[(usize, Shape)]| -> Vec<(usize, Aabb)> {
        shapes
            .iter()
            .map(|(i, s)| (*i, bounds(s).expect("bounded")))
            .collect()
    };
    let mut bounded_after = boxed(&after);
    bounded_after.reverse();
    let mut patched_lights = 0;
    for light in &lights {
        let build = |shapes: &[(usize, Shape)], bounded: &[(usize, Aabb)]| {
            let shape = |i: usize| shapes.iter().find(|(j, _)| *j == i).expect("an object").1;
            Footprints::new(Vec3::ZERO, Vec3::Y, light, bounded, |i| {
                piece_boxes(&shape(i))
            })
            .expect("lit")
        };
        let was = build(&before, &boxed(&before));
        let fresh = build(&after, &bounded_after);
        let shape = |i: usize| after.iter().find(|(j, _)| *j == i).expect("an object").1;
        let Some(patched) = was
            .clone()
            .with_moved(&moved, &bounded_after, |i| piece_boxes(&shape(i)))
        else {
            // Declined only where the move changed the grid's bounds (here
            // the low light's, whose bounds ball 4's strings' shadows set).
            assert_ne!(was.bounds, fresh.bounds, "{light:?}");
            continue;
        };
        patched_lights += 1;
        assert_eq!(
            (patched.n, patched.min, patched.inv_cell),
            (fresh.n, fresh.min, fresh.inv_cell)
        );
        assert_eq!(lists(&patched), lists(&fresh), "{light:?}");
        // The move changed some cells' lists.
        assert_ne!(lists(&was), lists(&fresh), "{light:?}");
        // Moved again, and back: the lists are those of the first frame.
        let back = patched
            .with_moved(&moved, &boxed(&before), |i| {
                piece_boxes(&before.iter().find(|(j, _)| *j == i).expect("an object").1)
            })
            .expect("the grid's bounds stay");
        assert_eq!(lists(&back), lists(&was), "{light:?}");
    }
    assert_eq!(patched_lights, 2);
}

#[test]
fn footprints_are_built_afresh_when_a_moved_object_changes_the_grids_bounds() {
    let light = Light::Point {
        position: Vec3::new(0.7, 0.6, 0.5),
        color: Vec3::ONE,
    };
    let xs: Vec<f32> = (0..5).map(|k| 0.04 * (k as f32 - 2.0)).collect();
    let before = row(&xs);
    // The last ball swings out past the row's end.
    let mut out = xs.clone();
    out[4] += 0.05;
    let after = row(&out);
    let shape_in = |shapes: &[(usize, Shape)], i: usize| {
        shapes.iter().find(|(j, _)| *j == i).expect("an object").1
    };
    let boxed = |shapes: &[(usize, Shape)]| -> Vec<(usize, Aabb)> {
        shapes
            .iter()
            .map(|(i, s)| (*i, bounds(s).expect("bounded")))
            .collect()
    };
    let was = Footprints::new(Vec3::ZERO, Vec3::Y, &light, &boxed(&before), |i| {
        piece_boxes(&shape_in(&before, i))
    })
    .expect("lit");
    let moved = [13, 14, 15];
    assert!(
        was.with_moved(&moved, &boxed(&after), |i| piece_boxes(&shape_in(
            &after, i
        )))
        .is_none()
    );
}
