//! The common overrides applied to a loaded config: each flag replaces one field,
//! then the config is validated again, and an error names the flag that set the
//! field with its valid range (or the field of the asset a flag made invalid).

use super::args::{AaFlag, Common, ContactFlag, IntegratorFlag, Short};
use crate::config::{Config, ConfigSource, ContactModel, FieldError};
use crate::physics::Integrator;

/// Bad input from a flag or the config: exit code 2.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// The config asset.
    #[error(transparent)]
    Config(#[from] crate::config::ConfigError),
    /// A flag out of range.
    #[error("{0}")]
    Flag(String),
}

/// A count flag as the config's integer type; a negative count becomes `fail`, a
/// value the field's check refuses, so that the flag's message shows its range.
fn count<T: TryFrom<i64>>(v: i64, fail: T) -> T {
    T::try_from(v).unwrap_or(fail)
}

impl Common {
    /// The names of the override flags given, in schema order.
    #[must_use]
    pub fn given_flags(&self) -> Vec<&'static str> {
        let mut flags: Vec<&'static str> = self.given().into_iter().map(|g| g.1).collect();
        if self.mute {
            flags.push("--mute");
        }
        flags
    }

    /// The flags given, as `(config field path, flag name, value as typed)`.
    fn given(&self) -> Vec<(&'static str, &'static str, String)> {
        let mut out = Vec::new();
        let mut add = |field, flag, v: Option<String>| {
            if let Some(v) = v {
                out.push((field, flag, v));
            }
        };
        add("cradle.balls", "--balls", self.balls.map(|v| v.to_string()));
        add("start.lift", "--lift", self.lift.map(|v| v.to_string()));
        add("start.angle_deg", "--angle", self.angle.map(|v| v.short()));
        add("cradle.gap", "--gap", self.gap.map(|v| v.short()));
        add(
            "contact.model",
            "--contact",
            self.contact.map(|v| format!("{v:?}").to_lowercase()),
        );
        add(
            "physics.integrator",
            "--integrator",
            self.integrator
                .map(|v| crate::physics::Integrator::from(v).name().to_owned()),
        );
        add("physics.dt", "--dt", self.dt.map(|v| v.short()));
        add(
            "render.threads",
            "--threads",
            self.threads.map(|v| v.to_string()),
        );
        add("render.width", "--width", self.width.map(|v| v.to_string()));
        add(
            "render.height",
            "--height",
            self.height.map(|v| v.to_string()),
        );
        add(
            "render.samples",
            "--samples",
            self.samples.map(|v| v.to_string()),
        );
        add(
            "render.adaptive",
            "--aa",
            self.aa.map(|v| format!("{v:?}").to_lowercase()),
        );
        out
    }

    /// Loads the config this command line names and applies the overrides.
    ///
    /// # Errors
    /// A bad asset, or a flag out of range (with the flag's valid range).
    pub fn load(&self) -> Result<(Config, ConfigSource), InputError> {
        let source = ConfigSource::resolve(self.config.as_deref());
        let mut config = source.load()?;
        self.apply(&mut config)?;
        Ok((config, source))
    }

    /// Applies the overrides to `config` and validates the result.
    ///
    /// # Errors
    /// A flag out of range, named with its valid range; or a field of the asset that
    /// a flag made invalid (e.g. `--balls 2` with `lift: 3`).
    pub fn apply(&self, config: &mut Config) -> Result<(), InputError> {
        if let Some(v) = self.balls {
            config.cradle.balls = count(v, 0);
        }
        if let Some(v) = self.lift {
            config.start.lift = count(v, usize::MAX);
        }
        if let Some(v) = self.angle {
            config.start.angle_deg = v;
        }
        if let Some(v) = self.gap {
            config.cradle.gap = v;
        }
        if let Some(v) = self.contact {
            config.contact.model = v.into();
        }
        if let Some(v) = self.integrator {
            config.physics.integrator = v.into();
        }
        if let Some(v) = self.dt {
            config.physics.dt = v;
        }
        if let Some(v) = self.threads {
            config.render.threads = count(v, usize::MAX);
        }
        if let Some(v) = self.width {
            config.render.width = count(v, 0);
        }
        if let Some(v) = self.height {
            config.render.height = count(v, 0);
        }
        if let Some(v) = self.samples {
            config.render.samples = count(v, 0);
        }
        if let Some(v) = self.aa {
            config.render.adaptive = matches!(v, AaFlag::Adaptive);
        }
        let Err(errors) = config.validate() else {
            return Ok(());
        };
        let given = self.given();
        Err(InputError::Flag(
            errors
                .iter()
                .map(|e| flag_message(e, &given))
                .collect::<Vec<_>>()
                .join("\n"),
        ))
    }
}

/// Names the flag that set a field; or, for a field of the asset, the flags
/// its rule names (`--integrator rk4` for a dissipation that needs the exact
/// integrator), else the flags given, else that the asset holds it.
fn flag_message(e: &FieldError, given: &[(&str, &str, String)]) -> String {
    if let Some((_, flag, raw)) = given.iter().find(|(field, _, _)| *field == e.path) {
        format!("{flag} {raw}: not allowed; allowed: {}", e.allowed)
    } else {
        let named: Vec<String> = given
            .iter()
            .filter(|(field, _, _)| e.allowed.contains(field))
            .map(|(_, flag, raw)| format!("{flag} {raw}"))
            .collect();
        let all: Vec<String> = given
            .iter()
            .map(|(_, flag, raw)| format!("{flag} {raw}"))
            .collect();
        match (named.is_empty(), all.is_empty()) {
            (false, _) => format!("{e} (the asset's value, refused with {})", named.join(", ")),
            (true, false) => format!("{e} (the asset's value, after {})", all.join(", ")),
            (true, true) => format!("{e} (in the asset)"),
        }
    }
}

impl From<ContactFlag> for ContactModel {
    fn from(v: ContactFlag) -> Self {
        match v {
            ContactFlag::Ideal => Self::Ideal,
            ContactFlag::Hertz => Self::Hertz,
        }
    }
}

impl From<IntegratorFlag> for Integrator {
    fn from(v: IntegratorFlag) -> Self {
        match v {
            IntegratorFlag::Exact => Self::Exact,
            IntegratorFlag::Euler => Self::Euler,
            IntegratorFlag::Verlet => Self::Verlet,
            IntegratorFlag::Rk4 => Self::Rk4,
            IntegratorFlag::Yoshida4 => Self::Yoshida4,
        }
    }
}
