//! Output files: each written under a temporary name in its folder and renamed
//! into place only when complete, so that no file is ever half-written (a
//! failed write, a full disk or Ctrl-C leaves the old file, or none).
//! [`check_output`] refuses, before any work, a path that would replace the
//! config being read or a file that is not one of ours.

use std::fs::File;
use std::io::{BufWriter, Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use tempfile::NamedTempFile;

/// An output file that cannot be written.
#[derive(Debug, thiserror::Error)]
#[error("cannot write {}: {reason}", path.display())]
pub struct WriteError {
    /// The path.
    pub path: PathBuf,
    /// Why.
    pub reason: String,
    /// Whether the path itself is at fault (a bad name, a folder that is a file,
    /// no permission: bad input, exit code 2) rather than the writing (a full
    /// disk, an I/O error: exit code 1).
    pub bad_path: bool,
}

/// A path that must not or cannot be written: bad input.
pub(super) fn bad(path: &Path, reason: impl ToString) -> WriteError {
    WriteError {
        path: path.to_path_buf(),
        reason: reason.to_string(),
        bad_path: true,
    }
}

/// A failure while encoding or writing: never the path's fault.
pub(super) fn fail(path: &Path, reason: impl ToString) -> WriteError {
    WriteError {
        path: path.to_path_buf(),
        reason: reason.to_string(),
        bad_path: false,
    }
}

/// An I/O failure: bad input where the path is to blame (no such folder, no
/// permission, a file where a folder should be), else a failure of the writing.
pub(super) fn io_fail(path: &Path, e: &std::io::Error) -> WriteError {
    use std::io::ErrorKind as K;
    let bad_path = matches!(
        e.kind(),
        K::PermissionDenied
            | K::NotFound
            | K::NotADirectory
            | K::IsADirectory
            | K::ReadOnlyFilesystem
            | K::InvalidFilename
    );
    WriteError {
        bad_path,
        ..fail(path, e)
    }
}

/// What a file holds: each kind has its extension and its signature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A PNG picture.
    Png,
    /// An animated GIF.
    Gif,
    /// An SVG plot.
    Svg,
    /// A WAV soundtrack.
    Wav,
}

impl Kind {
    pub(super) fn extension(self) -> &'static str {
        match self {
            Self::Png => "png",
            Self::Gif => "gif",
            Self::Svg => "svg",
            Self::Wav => "wav",
        }
    }

    /// Whether `head`, a file's first bytes, is a file of this kind.
    fn is_signed_by(self, head: &[u8]) -> bool {
        match self {
            Self::Png => head.starts_with(b"\x89PNG\r\n\x1a\n"),
            Self::Gif => head.starts_with(b"GIF87a") || head.starts_with(b"GIF89a"),
            Self::Svg => {
                let text = String::from_utf8_lossy(head);
                let t = text.trim_start();
                t.starts_with("<svg") || t.starts_with("<?xml")
            }
            Self::Wav => head.starts_with(b"RIFF") && head.get(8..12) == Some(b"WAVE"),
        }
    }
}

/// Checks that `path` can take a file of `kind`, before anything is computed: its
/// extension is the kind's; its folder exists (it is created) and is a folder; and
/// if a file is there already, it is not `input` (the config being read) and is a
/// file of this kind, so replacing it loses nothing of the user's.
///
/// # Errors
/// Any of these not holding, with what is allowed.
pub fn check_output(path: &Path, kind: Kind, input: Option<&Path>) -> Result<(), WriteError> {
    let ext = kind.extension();
    let ok = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(ext));
    if !ok {
        return Err(bad(path, format!("allowed: a .{ext} file name")));
    }
    create_folder(path)?;
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return Ok(());
    };
    if !meta.is_file() {
        return Err(bad(path, "something other than a file is there"));
    }
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if input.is_some_and(|i| same(path, i)) {
        return Err(bad(path, "it is the config being read"));
    }
    let mut head = [0u8; 16];
    let n = File::open(path)
        .and_then(|mut f| f.read(&mut head))
        .map_err(|e| io_fail(path, &e))?;
    if !kind.is_signed_by(&head[..n]) {
        return Err(bad(
            path,
            format!("a file that is not a .{ext} picture is there; refusing to replace it"),
        ));
    }
    Ok(())
}

/// Creates the folders above `path`, with a plain message when one of them is a
/// file.
pub(super) fn create_folder(path: &Path) -> Result<(), WriteError> {
    let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) else {
        return Ok(());
    };
    if let Some(file) = parent.ancestors().find(|a| a.is_file()) {
        return Err(bad(
            path,
            format!("{} is a file, not a folder", file.display()),
        ));
    }
    std::fs::create_dir_all(parent).map_err(|e| io_fail(path, &e))
}

/// Temporary files being written: Ctrl-C removes them.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Makes Ctrl-C, SIGTERM and SIGHUP remove the temporary files of unfinished
/// writes before the program ends (exit code 130), so that none is left behind.
pub fn clean_up_on_interrupt() {
    let handler = || {
        if let Ok(live) = LIVE.lock() {
            for p in live.iter() {
                let _ = std::fs::remove_file(p);
            }
        }
        std::process::exit(130);
    };
    if let Err(e) = ctrlc::set_handler(handler) {
        tracing::debug!("Ctrl-C clean-up is off: {e}");
    }
}

/// A file being written under a temporary name beside `path` (a
/// `tempfile::NamedTempFile`, which removes itself when dropped unfinished);
/// [`Self::commit`] renames it into place.
pub struct AtomicFile {
    path: PathBuf,
    tmp: PathBuf,
    out: Option<BufWriter<NamedTempFile>>,
}

impl AtomicFile {
    /// Starts writing what will become `path` (its folder must exist).
    ///
    /// # Errors
    /// When the temporary file cannot be created.
    pub fn create(path: &Path) -> Result<Self, WriteError> {
        let name = path
            .file_name()
            .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
        let dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let file = tempfile::Builder::new()
            .prefix(&format!(".{name}."))
            .suffix(".part")
            .make_in(dir, |tmp| {
                // Known before it exists: a signal between the two would
                // otherwise leave an empty file no one removes.
                if let Ok(mut live) = LIVE.lock() {
                    live.push(tmp.to_path_buf());
                }
                File::create_new(tmp).inspect_err(|_| forget(tmp))
            })
            .map_err(|e| io_fail(path, &e))?;
        Ok(Self {
            path: path.to_path_buf(),
            tmp: file.path().to_path_buf(),
            out: Some(BufWriter::new(file)),
        })
    }

    /// Flushes the file to disk and renames it into place.
    ///
    /// # Errors
    /// When writing, flushing or renaming fails (the temporary file is removed).
    pub fn commit(mut self) -> Result<(), WriteError> {
        let out = self.out.take().expect("taken only here");
        let file = out
            .into_inner()
            .map_err(|e| io_fail(&self.path, e.error()))?;
        file.as_file()
            .sync_all()
            .map_err(|e| io_fail(&self.path, &e))?;
        file.persist(&self.path)
            .map_err(|e| io_fail(&self.path, &e.error))?;
        Ok(())
    }
}

/// Stops tracking temporary file `tmp` (renamed or removed).
fn forget(tmp: &Path) {
    if let Ok(mut live) = LIVE.lock() {
        live.retain(|p| p != tmp);
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.out.as_mut().expect("taken only by commit").write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.out.as_mut().expect("taken only by commit").flush()
    }
}

impl Seek for AtomicFile {
    fn seek(&mut self, pos: std::io::SeekFrom) -> std::io::Result<u64> {
        self.out.as_mut().expect("taken only by commit").seek(pos)
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // Unfinished, the temporary file removes itself as it drops; renamed,
        // it is gone under that name.
        self.out = None;
        forget(&self.tmp);
    }
}

/// Writes `bytes` as `path`, atomically.
///
/// # Errors
/// When the file cannot be written.
pub fn write_all(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    create_folder(path)?;
    let mut f = AtomicFile::create(path)?;
    f.write_all(bytes).map_err(|e| io_fail(path, &e))?;
    f.commit()
}
