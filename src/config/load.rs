//! Reading the asset: which file, parsing RON, and errors that say where.

use super::Config;
use super::locate::locate;
use super::validate::FieldError;
use std::fmt;
use std::path::{Path, PathBuf};

/// The default asset, built into the binary so that it runs from anywhere.
pub const DEFAULT_ASSET: &str = include_str!("../../assets/cradle.ron");

/// Where a config came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ConfigSource {
    /// A file on disk.
    File(PathBuf),
    /// The copy of `assets/cradle.ron` built into the binary.
    Builtin,
}

impl ConfigSource {
    /// `--config PATH` if given, else `assets/cradle.ron` in the working directory
    /// if present, else the built-in default.
    #[must_use]
    pub fn resolve(flag: Option<&Path>) -> Self {
        match flag {
            Some(p) => Self::File(p.to_path_buf()),
            None if Path::new("assets/cradle.ron").is_file() => {
                Self::File(PathBuf::from("assets/cradle.ron"))
            }
            None => Self::Builtin,
        }
    }

    /// Reads and validates the config.
    ///
    /// # Errors
    /// When the file cannot be read, is not RON for a [`Config`], or has a field out
    /// of range.
    pub fn load(&self) -> Result<Config, ConfigError> {
        match self {
            Self::File(p) => load_file(p),
            Self::Builtin => parse(DEFAULT_ASSET, "<built-in assets/cradle.ron>"),
        }
    }
}

impl fmt::Display for ConfigSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::File(p) => write!(f, "{}", p.display()),
            Self::Builtin => write!(f, "the built-in default asset"),
        }
    }
}

/// A config that could not be used. Every variant is bad input (exit code 2).
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// The file could not be read.
    #[error("{file}: cannot read the config: {source}")]
    Read {
        file: String,
        #[source]
        source: std::io::Error,
    },
    /// The file is not UTF-8 text.
    #[error("{file}: the config is not UTF-8 text (is it a binary file?)")]
    NotText { file: String },
    /// The RON does not parse into a config.
    #[error("{file}:{line}:{col}: {message}")]
    Syntax {
        file: String,
        line: usize,
        col: usize,
        message: String,
    },
    /// Fields out of range.
    #[error("{}", invalid_message(file, errors))]
    Invalid {
        file: String,
        /// Each error with its line and column in the file, if it is written there.
        errors: Vec<(Option<(usize, usize)>, FieldError)>,
    },
}

fn invalid_message(file: &str, errors: &[(Option<(usize, usize)>, FieldError)]) -> String {
    errors
        .iter()
        .map(|(at, e)| match at {
            Some((l, c)) => format!("{file}:{l}:{c}: {e}"),
            None => {
                format!("{file}: {e} (not in the file: its default conflicts with another field)")
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Reads, parses and validates a config file.
///
/// # Errors
/// See [`ConfigSource::load`].
pub fn load_file(path: &Path) -> Result<Config, ConfigError> {
    let file = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| ConfigError::Read {
        file: file.clone(),
        source,
    })?;
    let src = String::from_utf8(bytes).map_err(|_| ConfigError::NotText { file: file.clone() })?;
    parse(&src, &file)
}

/// Parses and validates config text; `file` names it in errors.
///
/// # Errors
/// See [`ConfigSource::load`].
pub fn parse(src: &str, file: &str) -> Result<Config, ConfigError> {
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let config: Config = options.from_str(src).map_err(|e| ConfigError::Syntax {
        file: file.to_owned(),
        line: e.span.start.line,
        col: e.span.start.col,
        message: e.code.to_string(),
    })?;
    config.validate().map_err(|errs| ConfigError::Invalid {
        file: file.to_owned(),
        errors: errs
            .into_iter()
            .map(|e| (locate(src, &e.path), e))
            .collect(),
    })?;
    Ok(config)
}
