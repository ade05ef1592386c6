//! Screenshots (the S key): what the window shows, HUD included, saved as
//! `newtons-cradle-YYYYMMDD-HHMMSS.png` (UTC) in the working directory.

use crate::trace::Image;
use std::path::Path;

/// Saves the `width x height` RGBA8 `frame`; the log says where, or why not.
pub fn save(width: u32, height: u32, frame: &[u8]) {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let name = format!("newtons-cradle-{}.png", utc_stamp(secs));
    let img = Image {
        width,
        height,
        rgba: frame.to_vec(),
    };
    match crate::export::write_png(Path::new(&name), &img) {
        Ok(()) => tracing::info!("saved screenshot {name}"),
        Err(e) => tracing::error!("screenshot not saved: {e}"),
    }
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
    use super::utc_stamp;

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
