//! Screenshots (the S key): what the window shows, HUD included, saved as
//! `newtons-cradle-YYYYMMDD-HHMMSS.png` (UTC) in the working directory; and
//! the names of the other files saved so ([`save_named`]: the graphs' CSV).

use crate::trace::Image;
use std::path::Path;

/// Saves the `width x height` RGBA8 `frame` on a thread of its own, so that
/// encoding never stalls the swing; the log says where, or why not, and so
/// does `done` (the file's name, or the error), on that thread.
pub fn save(
    width: u32,
    height: u32,
    frame: &[u8],
    done: impl FnOnce(Result<String, String>) + Send + 'static,
) {
    let img = Image {
        width,
        height,
        rgba: frame.to_vec(),
    };
    let stamp = stamp_now();
    std::thread::spawn(move || {
        // One name at a time, so two saves in one second cannot pick the same.
        static NAMING: std::sync::Mutex<()> = std::sync::Mutex::new(());
        let _guard = NAMING.lock();
        let name = free_name(&stamp, |n| Path::new(n).exists());
        match crate::export::write_png(Path::new(&name), &img) {
            Ok(()) => {
                tracing::info!("saved screenshot {name}");
                done(Ok(name));
            }
            Err(e) => {
                tracing::error!("screenshot not saved: {e}");
                done(Err(e.to_string()));
            }
        }
    });
}

/// Writes `bytes` as `newtons-cradle-STAMP.EXT` in the working directory
/// (numbered as [`free_named`] does: never over a file); returns the name.
///
/// # Errors
/// The file cannot be written.
pub fn save_named(ext: &str, bytes: &[u8]) -> Result<String, crate::export::WriteError> {
    let name = free_named(&stamp_now(), ext, |n| Path::new(n).exists());
    crate::export::write_all(Path::new(&name), bytes).map(|()| name)
}

/// `newtons-cradle-STAMP.png`, or with `-2`, `-3`, .. when `taken` says the name
/// is in use: an existing file is never replaced.
#[must_use]
pub fn free_name(stamp: &str, taken: impl Fn(&str) -> bool) -> String {
    free_named(stamp, "png", taken)
}

/// `newtons-cradle-STAMP.EXT`, numbered as [`free_name`] does.
#[must_use]
pub fn free_named(stamp: &str, ext: &str, taken: impl Fn(&str) -> bool) -> String {
    let base = format!("newtons-cradle-{stamp}");
    (1..=u32::MAX)
        .map(|k| numbered(&base, k, ext))
        .find(|n| !taken(n))
        .expect("some numbered name is free")
}

/// The `k`-th name of a saved file: `BASE.EXT` for the first, `BASE-K.EXT` after.
#[must_use]
pub fn numbered(base: &str, k: u32, ext: &str) -> String {
    if k <= 1 {
        format!("{base}.{ext}")
    } else {
        format!("{base}-{k}.{ext}")
    }
}

/// `YYYYMMDD-HHMMSS` in UTC now.
#[must_use]
pub fn stamp_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    utc_stamp(secs)
}

/// `YYYYMMDD-HHMMSS` in UTC for `secs` seconds since 1970-01-01.
#[must_use]
pub fn utc_stamp(secs: u64) -> String {
    let (days, rem) = (secs / 86_400, secs % 86_400);
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days.cast_signed() + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}{month:02}{day:02}-{:02}{:02}{:02}",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::{free_name, utc_stamp};

    #[test]
    fn screenshots_in_one_second_get_names_of_their_own() {
        let taken = [
            "newtons-cradle-20261130-120000.png",
            "newtons-cradle-20261130-120000-2.png",
        ];
        let pick = |stamp: &str| free_name(stamp, |n| taken.contains(&n));
        assert_eq!(
            pick("20261130-120001"),
            "newtons-cradle-20261130-120001.png"
        );
        assert_eq!(
            pick("20261130-120000"),
            "newtons-cradle-20261130-120000-3.png"
        );
    }

    #[test]
    fn stamps_known_instants() {
        // Values from `date -u -d @SECS +%Y%m%d-%H%M%S`.
        assert_eq!(utc_stamp(0), "19700101-000000");
        assert_eq!(utc_stamp(951_782_400), "20000229-000000", "a leap day");
        assert_eq!(utc_stamp(1_798_761_599), "20261231-235959");
        assert_eq!(
            utc_stamp(4_107_542_400),
            "21000301-000000",
            "1900-style non-leap"
        );
    }
}
