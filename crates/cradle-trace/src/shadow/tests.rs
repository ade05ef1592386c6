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
