//! The screen half of the motion filter: a ball's screen box under each map
//! holds its image and no more, and so do its ellipse's rows; a row's runs
//! hold the pixels that see it.

use super::{Conic, Map, Piece, Spans, ball_box, maps, merged};
use crate::camera::CameraRays;
use crate::scene::{Camera, Light, Material, Object, Scene, Shape};
use glam::Vec3;

/// A floor, a ball above it, two lights (a point and a directional one).
fn scene() -> Scene {
    let m = Material {
        color: Vec3::splat(0.5),
        specular: None,
        reflective: 0.3,
        checker: None,
    };
    Scene {
        objects: vec![Object {
            shape: Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            material: m,
            moving: false,
        }],
        lights: vec![
            Light::Point {
                position: lights().0,
                color: Vec3::ONE,
            },
            Light::Directional {
                direction: lights().1,
                color: Vec3::ONE,
            },
        ],
        camera: Camera {
            position: Vec3::new(0.1, 0.36, 0.6),
            look_at: Vec3::new(0.0, 0.12, 0.0),
            fov_deg: 31.0,
        },
        background: Vec3::ZERO,
        size: (400, 200),
        max_depth: 3,
        samples: 1,
        adaptive: None,
        motion_bounds: None,
        coarse: 1,
    }
}

/// A map's image of point `p`, given the point light and the directional
/// light's direction.
type Image = fn(Vec3, Vec3, Vec3) -> Vec3;

/// The scene's point light and the directional light's direction.
fn lights() -> (Vec3, Vec3) {
    (
        Vec3::new(0.7, 0.6, 0.5),
        Vec3::new(0.3, -1.0, -0.2).normalize(),
    )
}

/// Each map's image of a point, worked out here on its own for the floor
/// y = 0: itself, mirrored, cast from the light, cast along the light.
const IMAGES: [(&str, Image); 4] = [
    ("eye", |p, _, _| p),
    ("mirror", |p, _, _| Vec3::new(p.x, -p.y, p.z)),
    ("cast", |p, l, _| l + (p - l) * (l.y / (l.y - p.y))),
    ("along", |p, _, d| p - d * (p.y / d.y)),
];

/// Points spread over the ball's surface (a Fibonacci sphere).
fn surface(c: Vec3, r: f32, n: usize) -> impl Iterator<Item = Vec3> {
    (0..n).map(move |i| {
        let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
        let a = i as f32 * 2.399_963;
        let s = (1.0 - z * z).sqrt();
        c + r * Vec3::new(s * a.cos(), z, s * a.sin())
    })
}

#[test]
fn a_balls_screen_box_holds_its_image_and_no_more_under_every_map() {
    let sc = scene();
    let cam = CameraRays::new(&sc.camera, sc.size.0, sc.size.1);
    let (c, r) = (Vec3::new(-0.05, 0.09, 0.01), 0.02);
    let (light, along) = lights();
    let all = maps(&sc);
    assert_eq!(all.len(), 4, "the eye, the floor's mirror, two casts");
    for ((name, image), m) in IMAGES.iter().zip(&all) {
        let [bx, by] = ball_box(&cam, (c, r), m).expect("a bounded image");
        let (mut lo, mut hi) = ((f32::MAX, f32::MAX), (f32::MIN, f32::MIN));
        for p in surface(c, r, 20_000) {
            let (x, y) = cam.project(image(p, light, along)).expect("in front");
            // Inside, to f32 rounding of a few hundred pixels.
            assert!(
                bx[0] - 1e-3 <= x && x <= bx[1] + 1e-3,
                "{name}: x {x} out of {bx:?}"
            );
            assert!(
                by[0] - 1e-3 <= y && y <= by[1] + 1e-3,
                "{name}: y {y} out of {by:?}"
            );
            (lo, hi) = ((lo.0.min(x), lo.1.min(y)), (hi.0.max(x), hi.1.max(y)));
        }
        // And tight: 20,000 points reach within a tenth of a pixel of
        // each side (the corners' box is pixels wider).
        for (edge, got) in [(lo.0, bx[0]), (hi.0, bx[1]), (lo.1, by[0]), (hi.1, by[1])] {
            assert!(
                (edge - got).abs() < 0.1,
                "{name}: side {got} but points reach {edge}"
            );
        }
    }
    // A light below the top of the ball: its shadow is unbounded.
    let low = Map::Cast {
        point: Vec3::ZERO,
        normal: Vec3::Y,
        from: Vec3::new(0.5, 0.1, 0.0),
    };
    let ball = Piece::Ball(c, r);
    assert!(ball.region(&cam, &low).is_none());
}

#[test]
fn a_balls_ellipse_holds_its_image_row_by_row_and_cuts_the_boxs_corners() {
    let sc = scene();
    let cam = CameraRays::new(&sc.camera, sc.size.0, sc.size.1);
    let (c, r) = (Vec3::new(-0.05, 0.09, 0.01), 0.02);
    let (light, along) = lights();
    for (i, ((_, image), m)) in IMAGES.iter().zip(&maps(&sc)).enumerate() {
        let conic = Conic::of_ball(&cam, (c, r), m).expect("an ellipse");
        let [bx, by] = ball_box(&cam, (c, r), m).expect("a bounded image");
        // Per row of the box, the points' span and the ellipse's.
        let rows = by[0].floor() as i32..by[1].ceil() as i32;
        let mut seen = vec![(f32::MAX, f32::MIN); rows.len()];
        for p in surface(c, r, 20_000) {
            let (x, y) = cam.project(image(p, light, along)).expect("in front");
            let k = (y.floor() as i32 - rows.start) as usize;
            seen[k] = (seen[k].0.min(x), seen[k].1.max(x));
        }
        let (mut area, mut boxed) = (0.0, 0.0);
        for (k, &(lo, hi)) in seen.iter().enumerate() {
            let y = (rows.start + k as i32) as f32;
            let got = conic.band_x((y, y + 1.0));
            boxed += bx[1] - bx[0];
            let Some((l, r)) = got else {
                assert!(
                    lo > hi,
                    "map {i}, row {y}: points at {lo}..{hi}, no ellipse"
                );
                continue;
            };
            area += r - l;
            // Holds every point (to f32 rounding), and no more than a pixel
            // beyond them where the row holds many.
            assert!(
                l - 1e-3 <= lo && hi <= r + 1e-3,
                "map {i}, row {y}: {lo}..{hi} out of {l}..{r}"
            );
            if hi - lo > 10.0 {
                assert!(
                    lo - l < 1.0 && r - hi < 1.0,
                    "map {i}, row {y}: {l}..{r} for {lo}..{hi}"
                );
            }
        }
        // An ellipse fills at most pi / 4 of its box (plus the rows' steps).
        assert!(area < 0.85 * boxed, "map {i}: {area} of the box's {boxed}");
    }
}

#[test]
fn sure_runs_hold_pixels_whose_centre_ray_meets_the_ball_or_its_mirror_image() {
    let sc = scene();
    let cam = CameraRays::new(&sc.camera, sc.size.0, sc.size.1);
    let (c, r) = (Vec3::new(0.03, 0.1, 0.0), 0.02);
    // The ball's image in the floor (y = 0): the camera ray, straight on past
    // the floor, meets the mirrored ball where the mirror ray meets the ball.
    let image = Vec3::new(c.x, -c.y, c.z);
    let spans = Spans::new(&cam, &sc, Some(&[Piece::Ball(c, r)]));
    let meets = |x: u32, y: u32, centre: Vec3| {
        let ray = cam.ray(x as f32 + 0.5, y as f32 + 0.5);
        let oc = ray.origin - centre;
        let b = oc.dot(ray.dir);
        b * b - (oc.length_squared() - r * r) >= 0.0
    };
    let (mut sure, mut seen) = (0, 0);
    for y in 0..sc.size.1 {
        let (runs, sures) = (spans.row(y as usize), spans.sure_row(y as usize));
        let within = |x: u32, rs: &[(u32, u32)]| rs.iter().any(|&(a, b)| a <= x && x < b);
        for x in 0..sc.size.0 {
            let on = meets(x, y, c) || meets(x, y, image);
            seen += usize::from(on);
            if within(x, sures) {
                sure += 1;
                assert!(within(x, runs), "pixel ({x}, {y}) sure but in no run");
                assert!(on, "pixel ({x}, {y}) sure but its centre ray misses");
            }
        }
    }
    // All but a pixel's ring round each image: most of them (here the ball
    // is about 22 pixels across).
    assert!(seen > 400, "{seen} pixels see the ball or its image");
    assert!(sure * 10 > seen * 7, "{sure} sure of {seen}");
}

#[test]
fn spans_hold_every_pixel_whose_camera_ray_meets_the_ball() {
    let sc = scene();
    let cam = CameraRays::new(&sc.camera, sc.size.0, sc.size.1);
    let (c, r) = (Vec3::new(0.03, 0.1, 0.0), 0.02);
    let spans = Spans::new(&cam, &sc, Some(&[Piece::Ball(c, r)]));
    let (mut met, mut inside) = (0, 0);
    for y in 0..sc.size.1 {
        let runs = spans.row(y as usize);
        for w in runs.windows(2) {
            assert!(w[0].1 < w[1].0, "row {y}: runs ascend, apart");
        }
        let within = |x: u32| runs.iter().any(|&(a, b)| a <= x && x < b);
        for x in 0..sc.size.0 {
            inside += usize::from(within(x));
            // Ray and ball, by the quadratic's discriminant, at the pixel's
            // centre and its corners (samples lie anywhere in it).
            let sees = |(dx, dy): (f32, f32)| {
                let ray = cam.ray(x as f32 + dx, y as f32 + dy);
                let oc = ray.origin - c;
                let b = oc.dot(ray.dir);
                b * b - (oc.length_squared() - r * r) >= 0.0
            };
            let corners = [(0.0, 0.0), (0.999, 0.0), (0.0, 0.999), (0.999, 0.999)];
            met += usize::from(sees((0.5, 0.5)));
            if sees((0.5, 0.5)) || corners.into_iter().any(sees) {
                assert!(within(x), "pixel ({x}, {y}) sees the ball");
            }
        }
    }
    assert!(met > 100, "{met} pixels see the ball");
    // The eye's, the mirror's and two shadows' boxes, not the picture.
    assert!(
        inside < 8 * met,
        "{inside} pixels in runs for {met} on the ball"
    );
    // Without pieces (a moved plane): every pixel.
    let every = Spans::new(&cam, &sc, None);
    assert!((0..200).all(|y| every.row(y) == [(0, 400)]));
    assert!(every.row(200).is_empty());
}

#[test]
fn a_slanted_rod_shows_as_a_thin_band_that_holds_it() {
    // The eye alone (no plane, no light): the rod's own band.
    let mut sc = scene();
    sc.objects.clear();
    sc.lights.clear();
    let cam = CameraRays::new(&sc.camera, sc.size.0, sc.size.1);
    let (a, b, r) = (
        Vec3::new(-0.12, 0.04, 0.0),
        Vec3::new(0.1, 0.22, 0.03),
        0.002,
    );
    let spans = Spans::new(&cam, &sc, Some(&[Piece::Rod(a, b, r)]));
    let within = |x: f32, y: f32| {
        spans
            .row(y as usize)
            .iter()
            .any(|&(p, q)| p as f32 <= x && x < q as f32)
    };
    // Points of the capsule's surface, along it and around it.
    let (w, (e1, e2)) = (
        (b - a).normalize(),
        (b - a).normalize().any_orthonormal_pair(),
    );
    let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for i in 0..=400 {
        for k in 0..16 {
            let turn = k as f32 * std::f32::consts::TAU / 16.0;
            let p = a.lerp(b, i as f32 / 400.0) + r * (e1 * turn.cos() + e2 * turn.sin());
            let (x, y) = cam.project(p).expect("in front");
            assert!(
                within(x, y),
                "a point of the rod at ({x}, {y}) is in no run"
            );
            (lo, hi) = (lo.min(Vec3::new(x, y, 0.0)), hi.max(Vec3::new(x, y, 0.0)));
        }
    }
    // The ends' caps too.
    for p in [a - w * r, b + w * r] {
        let (x, y) = cam.project(p).expect("in front");
        assert!(within(x, y), "a cap at ({x}, {y}) is in no run");
    }
    // A band, not the rod's screen box: a small part of it.
    let inside: u32 = (0..sc.size.1 as usize)
        .flat_map(|y| spans.row(y).iter().map(|&(p, q)| q - p))
        .sum();
    let boxed = (hi.x - lo.x) * (hi.y - lo.y);
    assert!(
        (inside as f32) < 0.25 * boxed,
        "{inside} pixels in runs, the box {boxed}"
    );
}

#[test]
fn a_string_whose_shadow_reaches_behind_the_eye_keeps_to_its_side_of_the_picture() {
    // Looking towards the point light, which throws a long string's shadow
    // back past the eye.
    let mut sc = scene();
    sc.camera = Camera {
        position: Vec3::new(0.0, 0.3, -0.5),
        look_at: Vec3::new(0.0, 0.1, 0.5),
        fov_deg: 60.0,
    };
    let cam = CameraRays::new(&sc.camera, sc.size.0, sc.size.1);
    let (a, b, r) = (Vec3::new(0.1, 0.4, 0.0), Vec3::new(0.1, 0.11, 0.0), 0.0008);
    let spans = Spans::new(&cam, &sc, Some(&[Piece::Rod(a, b, r)]));
    let within = |(x, y): (f32, f32)| {
        spans
            .row(y as usize)
            .iter()
            .any(|&(p, q)| p as f32 <= x && x < q as f32)
    };
    // Points of the string's shadow from the point light, those in front.
    let (light, _) = lights();
    let (e1, e2) = (b - a).normalize().any_orthonormal_pair();
    let (mut shown, mut behind) = (0, 0);
    for i in 0..=200 {
        for k in 0..8 {
            let turn = k as f32 * std::f32::consts::TAU / 8.0;
            let p = a.lerp(b, i as f32 / 200.0) + r * (e1 * turn.cos() + e2 * turn.sin());
            let cast = IMAGES[2].1(p, light, Vec3::ZERO);
            match cam.project(cast) {
                Some((x, y)) if (0.0..400.0).contains(&x) && (0.0..200.0).contains(&y) => {
                    assert!(within((x, y)), "the shadow at ({x}, {y}) is in no run");
                    shown += 1;
                }
                Some(_) => {}
                None => behind += 1,
            }
        }
    }
    assert!(
        shown > 100 && behind > 100,
        "{shown} shown, {behind} behind"
    );
    // Its side of the picture, not every pixel.
    let inside: u32 = (0..200)
        .flat_map(|y| spans.row(y).iter().map(|&(p, q)| q - p))
        .sum();
    assert!(
        inside < 400 * 200 / 4,
        "{inside} pixels in runs, {shown} shown"
    );
}

#[test]
fn merged_runs_join_where_they_meet_row_by_row_whatever_the_order() {
    // Row 2: 5..9 and 8..12 overlap, 12..14 touches; 20..22 stands apart.
    // Row 0: one run; row 1 and row 3 none.
    let cover = vec![(2, 20, 22), (2, 8, 12), (0, 1, 3), (2, 12, 14), (2, 5, 9)];
    let (runs, start) = merged(cover, 4);
    assert_eq!(runs, [(1, 3), (5, 14), (20, 22)]);
    assert_eq!(start, [0, 1, 1, 3, 3]);
    let (runs, start) = merged(Vec::new(), 2);
    assert!(runs.is_empty());
    assert_eq!(start, [0, 0, 0]);
}
