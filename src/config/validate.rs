//! Range checks of every config field. Each failure names the field's path
//! (`cradle.balls`, `lights[1].intensity`) and what is allowed, so that the loader
//! can point at the line and the CLI at the flag.

use super::{Config, ContactModel, LightConfig, MAX_BALLS, MaterialConfig, Rgb, Vec3, ranges};
use std::fmt;

/// The whole-number fields and what they allow: the messages for a value out of
/// range, and for one that is not a whole number at all (`balls: 2.5`), which
/// stops the parser before validation.
pub const WHOLE: [(&str, &str); 7] = [
    ("cradle.balls", "1..=200"),
    ("start.lift", "0..=balls"),
    ("render.width", "16..=8192 (pixels)"),
    ("render.height", "16..=8192 (pixels)"),
    ("render.max_depth", "0..=16"),
    ("render.samples", "1..=64"),
    ("render.threads", "0..=256 (0 = every core)"),
];

/// The largest lift angle (degrees): at 1e-3 degrees from the top the modulus of
/// the flight is 4e-11 from 1, thousands of ulps; much nearer, the round-off of
/// an impact can carry a ball over the top (seen at 179.999999).
pub const MAX_ANGLE_DEG: f64 = 179.999;

/// What the whole-number field `path` allows.
fn whole(path: &str) -> &'static str {
    WHOLE
        .iter()
        .find(|(p, _)| *p == path)
        .map_or("a whole number", |(_, allowed)| allowed)
}

/// One invalid field.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// Dotted path of the field, e.g. `cradle.radius` or `lights[2].position`.
    pub path: String,
    /// The value found, as text.
    pub found: String,
    /// What is allowed.
    pub allowed: String,
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "`{}` is {}; allowed: {}",
            self.path, self.found, self.allowed
        )
    }
}

/// Collects failures in field order.
pub(super) struct Checker(Vec<FieldError>);

impl Checker {
    pub(super) fn fail(&mut self, path: &str, found: impl fmt::Debug, allowed: &str) {
        self.0.push(FieldError {
            path: path.to_owned(),
            found: format!("{found:?}"),
            allowed: allowed.to_owned(),
        });
    }

    /// A finite number with `ok(v)`.
    pub(super) fn num(&mut self, path: &str, v: f64, ok: bool, allowed: &str) {
        if !v.is_finite() {
            self.fail(path, v, &format!("a finite number, {allowed}"));
        } else if !ok {
            self.fail(path, v, allowed);
        }
    }

    /// Three finite numbers, each within `+-limit`.
    fn vec3(&mut self, path: &str, v: Vec3, limit: f64) {
        if v.iter().any(|x| !x.is_finite() || x.abs() > limit) {
            self.fail(
                path,
                v,
                &format!("three numbers, each within +-{limit} (m)"),
            );
        }
    }

    fn rgb(&mut self, path: &str, c: Rgb) {
        if c.iter().any(|x| !x.is_finite() || !(0.0..=1.0).contains(x)) {
            self.fail(path, c, "three numbers in 0..=1 (linear RGB)");
        }
    }

    fn material(&mut self, path: &str, m: &MaterialConfig) {
        self.rgb(&format!("{path}.color"), m.color);
        if let Some(e) = m.specular {
            self.num(
                &format!("{path}.specular"),
                e,
                (1.0..=10000.0).contains(&e),
                "None or 1..=10000",
            );
        }
        self.num(
            &format!("{path}.reflective"),
            m.reflective,
            (0.0..=1.0).contains(&m.reflective),
            "0..=1",
        );
        if let Some(c) = m.checker {
            self.rgb(&format!("{path}.checker"), c);
        }
        self.num(
            &format!("{path}.checker_size"),
            m.checker_size,
            m.checker_size > 0.0,
            "> 0 (m)",
        );
    }
}

impl Config {
    /// Checks every field's range; returns all failures, in field order.
    ///
    /// # Errors
    /// The list of invalid fields, when there is any.
    #[expect(
        clippy::too_many_lines,
        reason = "one check per config field, in the order of the asset"
    )]
    pub fn validate(&self) -> Result<(), Vec<FieldError>> {
        let mut c = Checker(Vec::new());
        let k = &self.cradle;
        if !ranges::BALLS.contains(&k.balls) {
            c.fail("cradle.balls", k.balls, &format!("1..={MAX_BALLS}"));
        }
        // Ranges keep every mass, energy and period finite and normal, and the
        // work of a simulated second bounded (a pendulum of 1e-4 m under 1e4 m/s^2
        // swings 1600 times a second).
        c.num(
            "cradle.radius",
            k.radius,
            (1e-4..=10.0).contains(&k.radius),
            "1e-4..=10 (m)",
        );
        c.num(
            "cradle.density",
            k.density,
            (1.0..=1e5).contains(&k.density),
            "1..=1e5 (kg/m^3)",
        );
        // Checks against the radius only make sense once the radius itself is valid;
        // otherwise one typo would report four fields.
        let r_ok = k.radius.is_finite() && k.radius > 0.0;
        let r = if r_ok { k.radius } else { 0.0 };
        c.num(
            "cradle.length",
            k.length,
            k.length <= 1e4 && (!r_ok || k.length > r),
            &format!("> radius = {r} and <= 1e4 (m)"),
        );
        c.num(
            "cradle.gap",
            k.gap,
            ranges::GAP.contains(&k.gap),
            "0..=10 (m)",
        );
        if k.length.is_finite() {
            c.num(
                "cradle.pivot_height",
                k.pivot_height,
                k.pivot_height > k.length + r && k.pivot_height <= 2e4,
                &format!(
                    "> length + radius = {} (m), so balls clear the floor, and <= 2e4",
                    k.length + r
                ),
            );
        }
        c.num(
            "cradle.rail_spread",
            k.rail_spread,
            k.rail_spread <= 1e4 && (!r_ok || k.rail_spread > r),
            &format!("> radius = {r} and <= 1e4 (m)"),
        );
        c.num(
            "cradle.gravity",
            k.gravity,
            (1e-3..=1e4).contains(&k.gravity),
            "1e-3..=1e4 (m/s^2)",
        );
        c.num(
            "cradle.string_radius",
            k.string_radius,
            k.string_radius > 0.0 && (!r_ok || k.string_radius < r),
            &format!("> 0 and < radius = {r} (m)"),
        );
        c.num(
            "cradle.frame_radius",
            k.frame_radius,
            k.frame_radius > 0.0 && k.frame_radius <= 10.0,
            "> 0 and <= 10 (m)",
        );

        let s = &self.start;
        if ranges::BALLS.contains(&k.balls) && s.lift > k.balls {
            c.fail(
                "start.lift",
                s.lift,
                &format!("0..={} (the number of balls)", k.balls),
            );
        }
        c.num(
            "start.angle_deg",
            s.angle_deg,
            ranges::ANGLE_DEG.contains(&s.angle_deg),
            "0..=179.999 (degrees; nearer the top, round-off in the impacts can carry a ball over it)",
        );

        let ct = &self.contact;
        if ct.model == ContactModel::Hertz && ct.restitution != 1.0 {
            c.fail(
                "contact.restitution",
                ct.restitution,
                "1 with contact.model hertz (Hertz contact is elastic); 0..=1 with ideal",
            );
        }
        c.num(
            "contact.restitution",
            ct.restitution,
            ranges::RESTITUTION.contains(&ct.restitution),
            "0..=1",
        );
        c.num(
            "contact.youngs_modulus",
            ct.youngs_modulus,
            (1e5..=1e13).contains(&ct.youngs_modulus),
            "1e5..=1e13 (Pa)",
        );
        c.num(
            "contact.poisson_ratio",
            ct.poisson_ratio,
            (0.0..0.5).contains(&ct.poisson_ratio),
            "0 <= nu < 0.5",
        );

        self.check_damping(&mut c);

        let dt = self.physics.dt;
        c.num(
            "physics.dt",
            dt,
            (1e-7..=0.1).contains(&dt),
            "1e-7..=0.1 (s)",
        );

        let r = &self.render;
        if !(16..=8192).contains(&r.width) {
            c.fail("render.width", r.width, whole("render.width"));
        }
        if !(16..=8192).contains(&r.height) {
            c.fail("render.height", r.height, whole("render.height"));
        }
        if r.max_depth > 16 {
            c.fail("render.max_depth", r.max_depth, whole("render.max_depth"));
        }
        if !ranges::SAMPLES.contains(&r.samples) {
            c.fail("render.samples", r.samples, whole("render.samples"));
        }
        c.num(
            "render.adaptive_threshold",
            r.adaptive_threshold,
            (0.0..=1.0).contains(&r.adaptive_threshold),
            "0..=1 (sRGB difference)",
        );
        if r.threads > 256 {
            c.fail("render.threads", r.threads, whole("render.threads"));
        }
        c.rgb("render.background", r.background);

        let cam = &self.camera;
        // The tracer works in f32: hit points round to ulps of the eye's distance
        // (1e-6 m at 10 m; the hit tests keep them that close to the surface), and
        // a 2 cm ball's normals with them; within 10 m, a tenth of the 2e-5 m that
        // secondary rays start off the surface, so no speckled self-shadowing.
        // An eye too near its target has no direction.
        c.vec3("camera.position", cam.position, 10.0);
        c.vec3("camera.look_at", cam.look_at, 10.0);
        let far = cam
            .position
            .iter()
            .chain(&cam.look_at)
            .fold(0.0_f64, |m, x| m.max(x.abs()));
        let apart = cam
            .position
            .iter()
            .zip(&cam.look_at)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt();
        if apart < 1e-3_f64.max(1e-4 * far) {
            c.fail(
                "camera.look_at",
                cam.look_at,
                "a point at least 1e-3 m (and 1e-4 of the coordinates) from camera.position",
            );
        }
        c.num(
            "camera.fov_deg",
            cam.fov_deg,
            (1.0..=170.0).contains(&cam.fov_deg),
            "1..=170 (degrees)",
        );

        if self.lights.len() > 16 {
            c.fail("lights", self.lights.len(), "at most 16 lights");
        }
        for (i, light) in self.lights.iter().enumerate() {
            let p = format!("lights[{i}]");
            let (color, intensity) = match light {
                LightConfig::Ambient { color, intensity } => (color, intensity),
                LightConfig::Point {
                    position,
                    color,
                    intensity,
                } => {
                    c.vec3(&format!("{p}.position"), *position, 1e4);
                    (color, intensity)
                }
                LightConfig::Directional {
                    direction,
                    color,
                    intensity,
                } => {
                    c.vec3(&format!("{p}.direction"), *direction, 1e4);
                    if direction.iter().all(|x| x.abs() < 1e-6) {
                        c.fail(
                            &format!("{p}.direction"),
                            direction,
                            "a direction with a component of at least 1e-6",
                        );
                    }
                    (color, intensity)
                }
            };
            c.rgb(&format!("{p}.color"), *color);
            c.num(
                &format!("{p}.intensity"),
                *intensity,
                *intensity >= 0.0,
                ">= 0",
            );
        }

        let m = &self.materials;
        c.material("materials.ball", &m.ball);
        c.material("materials.string", &m.string);
        c.material("materials.frame", &m.frame);
        c.material("materials.floor", &m.floor);

        c.num(
            "sound.volume",
            self.sound.volume,
            ranges::VOLUME.contains(&self.sound.volume),
            "0..=1 (0 = silent)",
        );

        if c.0.is_empty() { Ok(()) } else { Err(c.0) }
    }
}
