//! Reading the asset: which file, parsing RON, and errors that say where.

use super::Config;
use super::locate::locate_exact;
use super::validate::{FieldError, WHOLE};
use std::fmt;
use std::io::Read;
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
    /// Not a regular file (a folder, FIFO or device), or too large to be a config.
    #[error("{file}: {reason}; allowed: a RON file of at most 1 MiB")]
    NotAFile { file: String, reason: String },
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
    let read = |source| ConfigError::Read {
        file: file.clone(),
        source,
    };
    let not_a_file = |reason: String| ConfigError::NotAFile {
        file: file.clone(),
        reason,
    };
    // A FIFO would block for ever and a device could be read without end: only
    // regular files, and no more than a config can sensibly be.
    let meta = std::fs::metadata(path).map_err(read)?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a folder"
        } else {
            "not a regular file"
        };
        return Err(not_a_file(format!("it is {kind}")));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_CONFIG_BYTES + 1).read_to_end(&mut bytes))
        .map_err(read)?;
    if bytes.len() as u64 > MAX_CONFIG_BYTES {
        return Err(not_a_file("it is larger than 1 MiB".to_owned()));
    }
    let src = String::from_utf8(bytes).map_err(|_| ConfigError::NotText { file: file.clone() })?;
    parse(&src, &file)
}

/// The parser's message, and when the error stands in the value of a whole-number
/// field (a fraction, a sign, too many digits), which field and what it allows.
/// The names a key whose value is a name allows (`model`: `ideal`, `hertz`).
fn names_of(key: &str) -> Option<String> {
    match key {
        "model" => Some("ideal, hertz".to_owned()),
        "integrator" => Some(
            crate::physics::Integrator::ALL
                .iter()
                .map(|i| i.name())
                .collect::<Vec<_>>()
                .join(", "),
        ),
        _ => None,
    }
}

fn syntax_message(src: &str, (line, col): (usize, usize), message: &str) -> String {
    let text: Vec<char> = src
        .lines()
        .nth(line.saturating_sub(1))
        .unwrap_or("")
        .chars()
        .collect();
    // The error stands in the value written from column `from`: nothing that ends
    // a value lies between them.
    let in_value = |from: usize| {
        from >= 1
            && from <= col
            && text[(from - 1).min(text.len())..col.saturating_sub(1).min(text.len())]
                .iter()
                .all(|c| !matches!(c, ',' | '(' | ')' | '[' | ']'))
    };
    let field = WHOLE
        .iter()
        .find(|(path, _)| locate_exact(src, path).is_some_and(|(l, c)| l == line && in_value(c)));
    if let Some((path, allowed)) = field {
        return format!("`{path}` must be a whole number; allowed: {allowed} ({message})");
    }
    // Otherwise name the key written before the error on its line, if any.
    let before: String = text.iter().take(col.saturating_sub(1)).collect();
    let key = before.rsplit_once(':').and_then(|(head, value)| {
        if value.contains([',', '(', ')', '[', ']']) {
            return None;
        }
        let name = head.trim_end();
        // After the last character that is not part of a key (any width).
        let start = name
            .char_indices()
            .rev()
            .find(|&(_, c)| !(c.is_alphanumeric() || c == '_'))
            .map_or(0, |(i, c)| i + c.len_utf8());
        Some(&name[start..]).filter(|k| !k.is_empty())
    });
    match key {
        // The keys whose values are names: say which, written bare.
        Some(k) if names_of(k).is_some() => format!(
            "in `{k}`: {message}; allowed: {} (names, without quotes)",
            names_of(k).unwrap_or_default()
        ),
        Some(k) => format!("in `{k}`: {message}"),
        None => message.to_owned(),
    }
}

/// The largest config file read (bytes).
const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// Parses and validates config text; `file` names it in errors.
///
/// # Errors
/// See [`ConfigSource::load`].
pub fn parse(src: &str, file: &str) -> Result<Config, ConfigError> {
    // Editors on Windows may start UTF-8 files with a byte-order mark.
    let src = src.strip_prefix('\u{feff}').unwrap_or(src);
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let config: Config = options.from_str(src).map_err(|e| {
        let (line, col) = (e.span.start.line, e.span.start.col);
        ConfigError::Syntax {
            file: file.to_owned(),
            line,
            col,
            message: syntax_message(src, (line, col), &e.code.to_string()),
        }
    })?;
    config.validate().map_err(|errs| ConfigError::Invalid {
        file: file.to_owned(),
        errors: errs
            .into_iter()
            .map(|e| (locate_exact(src, &e.path), e))
            .collect(),
    })?;
    Ok(config)
}
