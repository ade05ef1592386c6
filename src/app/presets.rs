//! The panel's presets (`assets/presets/*.ron`, built into the binary so that
//! the list works from any folder) and "save setup", which writes the panel's
//! state as a new asset. Window-free: configs in, configs and files out.

use crate::config::{self, Config, ConfigError};
use std::io::Write;
use std::path::{Path, PathBuf};

/// A preset: the name the panel lists, and the asset's text.
#[derive(Debug, Clone, Copy)]
pub struct Preset {
    /// The name shown (the file name without `.ron`).
    pub name: &'static str,
    /// The asset.
    text: &'static str,
}

/// The preset of `assets/presets/NAME.ron`, its text built in.
macro_rules! preset {
    ($name:literal) => {
        Preset {
            name: $name,
            text: include_str!(concat!("../../assets/presets/", $name, ".ron")),
        }
    };
}

/// The presets, in the panel's order.
pub const PRESETS: [Preset; 7] = [
    preset!("default"),
    preset!("realistic"),
    preset!("two-lifted"),
    preset!("three-lifted"),
    preset!("small-gaps"),
    preset!("hertz"),
    preset!("long-row"),
];

impl Preset {
    /// The preset's config, keeping the picture size and thread count of
    /// `current` (the window's, which a preset does not choose).
    ///
    /// # Errors
    /// The built-in asset does not parse or validate (a test guards each).
    pub fn config(&self, current: &Config) -> Result<Config, ConfigError> {
        let file = format!("assets/presets/{}.ron", self.name);
        let mut c = config::parse(self.text, &file)?;
        c.render.width = current.render.width;
        c.render.height = current.render.height;
        c.render.threads = current.render.threads;
        Ok(c)
    }
}

/// The asset text of `config`: every key, with a header that says what it is.
///
/// # Errors
/// RON cannot write the config (it always can: plain numbers, enums, lists).
pub fn setup_text(config: &Config) -> Result<String, ron::Error> {
    let body = ron::ser::to_string_pretty(config, ron::ser::PrettyConfig::default())?;
    Ok(format!(
        "// newtons-cradle setup, saved from the window's control panel.\n\
         // Run it with: newtons-cradle --config THIS_FILE\n\
         // assets/cradle.ron lists every key with its unit and range.\n{body}\n"
    ))
}

/// Writes `config` as a new asset `newtons-cradle-setup-STAMP.ron` in `dir`
/// (`-2`, `-3`, .. when the name is taken): the text goes to a hidden
/// temporary file first, then takes its name only where no file has it
/// (`persist_noclobber`). Returns the path written.
///
/// # Errors
/// The folder cannot be written.
pub fn save_setup(config: &Config, dir: &Path, stamp: &str) -> std::io::Result<PathBuf> {
    let text = setup_text(config).map_err(std::io::Error::other)?;
    // Dropped unnamed (any error), the temporary file goes.
    let mut tmp = tempfile::Builder::new()
        .prefix(".newtons-cradle-setup-")
        .suffix(".part")
        .tempfile_in(dir)?;
    tmp.write_all(text.as_bytes())?;
    for k in 1u32.. {
        let name = super::screenshot::numbered(&format!("newtons-cradle-setup-{stamp}"), k, "ron");
        let path = dir.join(name);
        match tmp.persist_noclobber(&path) {
            Ok(_) => return Ok(path),
            Err(e) if e.error.kind() == std::io::ErrorKind::AlreadyExists => tmp = e.file,
            Err(e) => return Err(e.error),
        }
    }
    unreachable!("some numbered name is free")
}

#[cfg(test)]
mod tests {
    use super::{PRESETS, save_setup};
    use crate::config::{Config, ContactModel, parse};

    #[test]
    fn every_preset_loads_and_keeps_the_windows_picture_size() {
        let mut window = Config::default();
        (
            window.render.width,
            window.render.height,
            window.render.threads,
        ) = (480, 240, 1);
        let configs: Vec<Config> = PRESETS
            .iter()
            .map(|p| p.config(&window).expect(p.name))
            .collect();
        for c in &configs {
            assert_eq!(
                (c.render.width, c.render.height, c.render.threads),
                (480, 240, 1)
            );
        }
        let by_name = |n: &str| &configs[PRESETS.iter().position(|p| p.name == n).expect(n)];
        let mut default = Config::default();
        (
            default.render.width,
            default.render.height,
            default.render.threads,
        ) = (480, 240, 1);
        assert_eq!(*by_name("default"), default);
        assert_eq!(by_name("two-lifted").start.lift, 2);
        assert_eq!(by_name("three-lifted").start.lift, 3);
        assert!(by_name("small-gaps").cradle.gap > 0.0);
        assert_eq!(by_name("hertz").contact.model, ContactModel::Hertz);
        assert!(by_name("realistic").cradle_params().dissipative());
        assert!(by_name("long-row").cradle.balls >= 50);
    }

    #[test]
    fn a_saved_setup_reads_back_as_the_same_config_and_never_replaces_a_file() {
        let dir = std::env::temp_dir().join(format!("nc-setup-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let mut c = Config::default();
        c.cradle.balls = 9;
        c.contact.model = ContactModel::Hertz;
        let taken = dir.join("newtons-cradle-setup-20261203-101010.ron");
        std::fs::write(&taken, "mine").expect("write");
        let path = save_setup(&c, &dir, "20261203-101010").expect("saved");
        assert_eq!(path, dir.join("newtons-cradle-setup-20261203-101010-2.ron"));
        assert_eq!(
            std::fs::read_to_string(&taken).expect("read"),
            "mine",
            "untouched"
        );
        let text = std::fs::read_to_string(&path).expect("read");
        assert_eq!(parse(&text, "saved").expect("parses"), c);
        let left: Vec<_> = std::fs::read_dir(&dir).expect("list").collect();
        assert_eq!(left.len(), 2, "no temporary file left");
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
