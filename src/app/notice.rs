//! Short notices on screen: what an action did ("saved newtons-cradle-...png",
//! "reset", "preset: realistic"), shown for a couple of seconds at the bottom of
//! the picture and then gone. The session keeps them; the window draws them
//! and wakes when the oldest expires, so a paused window clears it too.
//! Window-free.

use std::time::{Duration, Instant};

/// How long a notice stays on screen.
pub const SHOWN_FOR: Duration = Duration::from_millis(2500);

/// At most this many notices show at once; a newer one pushes the oldest out.
const MOST: usize = 3;

/// The colour of a notice that reports a success, and of one that reports a
/// refusal or failure.
pub const GOOD: [u8; 3] = [150, 230, 160];
/// See [`GOOD`].
pub const BAD: [u8; 3] = [255, 140, 120];

/// One notice: its text, colour and when it goes.
#[derive(Debug, Clone, PartialEq)]
struct Notice {
    text: String,
    color: [u8; 3],
    until: Instant,
}

/// The notices on screen now.
#[derive(Debug, Default)]
pub struct Notices {
    shown: Vec<Notice>,
}

impl Notices {
    /// Shows `text` in `color` from `now` on, for [`SHOWN_FOR`].
    pub fn show(&mut self, text: impl Into<String>, color: [u8; 3], now: Instant) {
        let text = text.into();
        tracing::info!("notice: {text}");
        if self.shown.len() == MOST {
            self.shown.remove(0);
        }
        self.shown.push(Notice {
            text,
            color,
            until: now + SHOWN_FOR,
        });
    }

    /// The notices still showing at `now`, oldest first; drops the rest.
    pub fn at(&mut self, now: Instant) -> Vec<(String, [u8; 3])> {
        self.shown.retain(|n| n.until > now);
        self.shown
            .iter()
            .map(|n| (n.text.clone(), n.color))
            .collect()
    }

    /// When the next notice goes (the window wakes then to clear it).
    #[must_use]
    pub fn next_change(&self) -> Option<Instant> {
        self.shown.iter().map(|n| n.until).min()
    }
}

#[cfg(test)]
mod tests {
    use super::{GOOD, Notices, SHOWN_FOR};
    use std::time::{Duration, Instant};

    #[test]
    fn a_notice_shows_for_its_time_and_then_goes() {
        let t0 = Instant::now();
        let mut n = Notices::default();
        assert!(n.at(t0).is_empty());
        assert_eq!(n.next_change(), None);
        n.show("saved a.png", GOOD, t0);
        assert_eq!(n.at(t0 + Duration::from_secs(1)).len(), 1);
        assert_eq!(n.next_change(), Some(t0 + SHOWN_FOR));
        assert!(n.at(t0 + SHOWN_FOR).is_empty(), "gone when its time is up");
        assert_eq!(n.next_change(), None);
    }

    #[test]
    fn at_most_three_show_and_the_newest_stays() {
        let t0 = Instant::now();
        let mut n = Notices::default();
        for i in 0..5 {
            n.show(format!("saved {i}"), GOOD, t0);
        }
        let texts: Vec<String> = n.at(t0).into_iter().map(|(t, _)| t).collect();
        assert_eq!(texts, ["saved 2", "saved 3", "saved 4"]);
    }
}
