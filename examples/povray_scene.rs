//! Writes the flat scene of one frame as a POV-Ray 3.7 scene file, so the speed
//! reference users know can render the same frame (`tools/povray-compare.sh`).
//!
//! `cargo run --release --example povray_scene -- [CONFIG] [TIME] > frame.pov`
//! (CONFIG: an asset, default `assets/cradle.ron`; TIME: simulated seconds of the
//! swing, default 0.5, the first frame `bench render` times.)
//!
//! The same shapes, lights (point lights cast shadows, no attenuation), camera and
//! mirror depth (`max_trace_level` = bounces + 1, POV-Ray counting the camera ray)
//! as the tracer's; the shading is POV-Ray's closest match (ambient, Lambert
//! diffuse, Phong highlight, mirror reflection with the local colour weighted by
//! `1 - reflective`). POV-Ray is left-handed, so every z is negated: the picture
//! is the same, not mirrored.

use glam::Vec3;
use newtons_cradle::config::ConfigSource;
use newtons_cradle::scene::CradleWorld;
use newtons_cradle::trace::{Light, Material, Scene, Shape};
use std::fmt::Write as _;
use std::path::PathBuf;

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let config = args.next().map(PathBuf::from);
    let time: f64 = match args.next() {
        Some(t) => t.parse()?,
        None => 0.5,
    };
    let config = ConfigSource::resolve(config.as_deref()).load()?;
    let mut world = CradleWorld::new(&config);
    world.set_running(true);
    world.show_at(time);
    print!("{}", pov(world.scene()));
    Ok(())
}

/// A point with z negated, as POV-Ray's `<x, y, z>`.
fn v(p: Vec3) -> String {
    format!("<{}, {}, {}>", p.x, p.y, -p.z)
}

/// A linear colour as POV-Ray's `rgb <r, g, b>`.
fn rgb(c: Vec3) -> String {
    format!("rgb <{}, {}, {}>", c.x, c.y, c.z)
}

/// The whole scene file.
fn pov(scene: &Scene) -> String {
    let (w, h) = scene.size;
    let aspect = w as f32 / h as f32;
    let half = (scene.camera.fov_deg.to_radians() / 2.0).tan();
    let horizontal = 2.0 * (half * aspect).atan().to_degrees();
    let ambient: Vec3 = scene
        .lights
        .iter()
        .map(|l| match *l {
            Light::Ambient { color } => color,
            _ => Vec3::ZERO,
        })
        .sum();
    let mut out = String::new();
    let _ = writeln!(
        out,
        "// newtons-cradle frame, written by examples/povray_scene.rs"
    );
    let _ = writeln!(
        out,
        "global_settings {{ assumed_gamma 1.0 max_trace_level {} ambient_light {} }}",
        scene.max_depth + 1,
        rgb(ambient)
    );
    let _ = writeln!(out, "background {{ {} }}", rgb(scene.background));
    let _ = writeln!(
        out,
        "camera {{ perspective location {} look_at {} right x*{aspect} up y angle {horizontal} }}",
        v(scene.camera.position),
        v(scene.camera.look_at)
    );
    for light in &scene.lights {
        match *light {
            Light::Ambient { .. } => {}
            Light::Point { position, color } => {
                let _ = writeln!(
                    out,
                    "light_source {{ {} color {} }}",
                    v(position),
                    rgb(color)
                );
            }
            Light::Directional { direction, color } => {
                let _ = writeln!(
                    out,
                    "light_source {{ {} color {} parallel point_at <0, 0, 0> }}",
                    v(-direction * 1000.0),
                    rgb(color)
                );
            }
        }
    }
    for object in &scene.objects {
        let shape = match object.shape {
            Shape::Sphere { centre, radius } => format!("sphere {{ {}, {radius}", v(centre)),
            Shape::Cylinder { a, b, radius } => {
                format!("cylinder {{ {}, {}, {radius}", v(a), v(b))
            }
            Shape::Plane { point, normal } => {
                format!("plane {{ {}, {}", v(normal), point.dot(normal))
            }
        };
        let _ = writeln!(out, "{shape} {} }}", texture(&object.material));
    }
    out
}

/// A material as a POV-Ray texture.
fn texture(m: &Material) -> String {
    let keep = 1.0 - m.reflective;
    let pigment = match m.checker {
        // POV-Ray's checker counts cells in x, y and z: shift it half a cell in y
        // so the floor (y = 0) lies inside one layer.
        Some((other, size)) => format!(
            "pigment {{ checker {} {} translate <0, 0.5, 0> scale {size} }}",
            rgb(m.color),
            rgb(other)
        ),
        None => format!("pigment {{ {} }}", rgb(m.color)),
    };
    let phong = m
        .specular
        .map_or(String::new(), |e| format!(" phong {keep} phong_size {e}"));
    format!(
        "texture {{ {pigment} finish {{ ambient {keep} diffuse {keep}{phong} reflection {} }} }}",
        m.reflective
    )
}
