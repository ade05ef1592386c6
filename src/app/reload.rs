//! Hot reload: watch the config's folder (editors save by renaming a temp file over
//! the original, which a watch on the file itself would miss), keep the events for
//! that file name, and wake the event loop once per burst of saves.

use notify::{RecursiveMode, Watcher};
use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;
use winit::event_loop::EventLoopProxy;

/// A burst of events within this long is one save.
const SETTLE: Duration = Duration::from_millis(150);

/// Starts watching `file`; each save sends `event` through `proxy`. The watcher
/// stops when the returned value is dropped.
///
/// # Errors
/// When the folder cannot be watched.
pub fn watch<E: Clone + Send + 'static>(
    file: &Path,
    proxy: EventLoopProxy<E>,
    event: E,
) -> notify::Result<notify::RecommendedWatcher> {
    let name = file.file_name().map(std::ffi::OsStr::to_os_string);
    let dir = match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => Path::new(".").to_path_buf(),
    };
    let (tx, rx) = mpsc::channel::<()>();
    let mut watcher = notify::recommended_watcher(move |res: notify::Result<notify::Event>| {
        if let Ok(ev) = res
            && !ev.kind.is_access()
            && ev
                .paths
                .iter()
                .any(|p| p.file_name().map(std::ffi::OsStr::to_os_string) == name)
        {
            let _ = tx.send(());
        }
    })?;
    watcher.watch(&dir, RecursiveMode::NonRecursive)?;
    std::thread::spawn(move || {
        while rx.recv().is_ok() {
            // Let the editor finish writing, then swallow the rest of the burst.
            std::thread::sleep(SETTLE);
            while rx.try_recv().is_ok() {}
            if proxy.send_event(event.clone()).is_err() {
                return;
            }
        }
    });
    Ok(watcher)
}
