//! A save of the replay (`super`): the kept frames of the last 10 seconds
//! written as an animated PNG at the times they were shown, and the clicks
//! heard with them as a WAV of the same name.

use super::ring::{Ring, SPAN, Segment, apply};
use crate::export::{ApngWriter, WriteError};
use crate::sound::synth::{Click, Timbre};
use crate::sound::track::Soundtrack;
use crate::trace::Image;
use std::path::{Path, PathBuf};

/// What a save wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Saved {
    /// The animated PNG, and the WAV when clicks were heard.
    pub png: PathBuf,
    pub wav: Option<PathBuf>,
    /// Frames and seconds.
    pub frames: usize,
    pub seconds: f64,
}

/// What a save writes.
pub(super) struct Kept {
    size: (u32, u32),
    bgra: bool,
    segments: Vec<Segment>,
    clicks: Vec<Click>,
}

impl Kept {
    /// A copy of what `ring` keeps, for a save.
    pub(super) fn of(ring: &Ring) -> Self {
        let raw: usize = ring
            .segments
            .iter()
            .flat_map(|s| s.deltas.iter().flat_map(|d| d.spans.iter()))
            .map(|s| (s.x1 - s.x0) as usize * 4)
            .sum();
        tracing::info!(
            "replay: {} frames kept in {:.1} MB ({} whole, and the changes of the rest: {:.1} MB of pixels, large ones deflated)",
            ring.segments
                .iter()
                .map(|s| s.deltas.len() + 1)
                .sum::<usize>(),
            ring.bytes as f64 / 1e6,
            ring.segments.len(),
            raw as f64 / 1e6
        );
        Self {
            size: ring.size,
            bgra: ring.bgra,
            segments: ring.segments.iter().cloned().collect(),
            clicks: ring.clicks.clone(),
        }
    }

    /// The time of the newest frame (s).
    fn end(&self) -> f64 {
        self.segments
            .last()
            .map_or(0.0, |s| s.deltas.last().map_or(s.at, |d| d.at))
    }

    /// Every kept frame of the last [`SPAN`] seconds in order, each with its
    /// time (s on the recording's clock).
    fn frames(&self) -> impl Iterator<Item = (f64, Vec<u8>)> + '_ {
        let from = self.end() - SPAN;
        let width = self.size.0;
        self.segments
            .iter()
            .flat_map(move |s| {
                let mut canvas = s.key.to_vec();
                std::iter::once((s.at, canvas.clone())).chain(s.deltas.iter().map(move |d| {
                    apply(&mut canvas, width, d);
                    (d.at, canvas.clone())
                }))
            })
            .skip_while(move |(at, _)| *at < from)
            .map(move |(at, mut frame)| {
                if self.bgra {
                    for p in frame.chunks_exact_mut(4) {
                        p.swap(0, 2);
                    }
                }
                (at, frame)
            })
    }

    /// Writes the animated PNG (and the WAV when clicks were heard).
    pub(super) fn write(&self, png: &Path, timbre: Timbre) -> Result<Saved, String> {
        if self.segments.is_empty() {
            return Err("nothing to save yet: the swing has not run".into());
        }
        let from = self.end() - SPAN;
        let times: Vec<f64> = self
            .segments
            .iter()
            .flat_map(|s| std::iter::once(s.at).chain(s.deltas.iter().map(|d| d.at)))
            .filter(|&t| t >= from)
            .collect();
        let (first, n) = (times[0], times.len());
        // The last frame is shown for as long as the frames before it were.
        let seconds = if n == 1 {
            1.0 / 60.0
        } else {
            (times[n - 1] - first) * n as f64 / (n - 1) as f64
        };
        let written = (|| -> Result<Option<PathBuf>, WriteError> {
            let mut apng = ApngWriter::create(png, self.size, n as u32, true)?;
            let mut frames = self.frames().peekable();
            let ms = |t: f64| ((t - first) * 1000.0).round();
            while let Some((t, rgba)) = frames.next() {
                let next = frames.peek().map_or(first + seconds, |f| f.0);
                let delay = (ms(next) - ms(t)).clamp(1.0, 65535.0) as u16;
                let img = Image {
                    width: self.size.0,
                    height: self.size.1,
                    rgba,
                };
                apng.push(&img, (delay, 1000))?;
            }
            apng.finish()?;
            let clicks: Vec<Click> = self
                .clicks
                .iter()
                .filter(|c| c.at >= first)
                .map(|c| Click {
                    at: c.at - first,
                    ..*c
                })
                .collect();
            if clicks.is_empty() {
                return Ok(None);
            }
            let wav = png.with_extension("wav");
            Soundtrack::laid(timbre, seconds, clicks).write(&wav)?;
            Ok(Some(wav))
        })();
        match written {
            Ok(wav) => Ok(Saved {
                png: png.to_path_buf(),
                wav,
                frames: n,
                seconds,
            }),
            Err(e) => Err(e.to_string()),
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::super::ring::{Ring, SPAN, Span};
    use super::{Click, Kept, Timbre};

    pub(in crate::app::replay) const W: u32 = 40;
    pub(in crate::app::replay) const H: u32 = 20;

    /// Frame `k`: a fixed pattern with a 3x3 block at x = k mod 37, y = 5, and
    /// pixel (0, 0) counting frames.
    pub(in crate::app::replay) fn frame(k: usize) -> Vec<u8> {
        let mut f: Vec<u8> = (0..W * H)
            .flat_map(|i| [(i % 251) as u8, (i / 7) as u8, 40, 255])
            .collect();
        let x0 = (k % 37) as u32;
        for y in 5..8 {
            for x in x0..x0 + 3 {
                let at = ((y * W + x) * 4) as usize;
                f[at..at + 4].copy_from_slice(&[255, 0, 0, 255]);
            }
        }
        f[0] = k as u8;
        f
    }

    /// Every row, whole: what may have changed when nothing narrower is known.
    fn rows() -> Vec<Span> {
        (0..H).map(|y| Span { y, x0: 0, x1: W }).collect()
    }

    /// Rows 0 and 5..8 whole: all that frame `k` changes after frame `k - 1`.
    fn touched() -> Vec<Span> {
        [0, 5, 6, 7].map(|y| Span { y, x0: 0, x1: W }).to_vec()
    }

    fn bytes_of(f: &[u8], spans: &[Span]) -> Vec<u8> {
        spans.iter().flat_map(|s| f[s.bytes(W)].to_vec()).collect()
    }

    #[test]
    fn a_ring_keeps_the_last_ten_seconds_of_frames_exactly() {
        let mut ring = Ring::default();
        let fps = 50.0;
        for k in 0..750 {
            let f = frame(k);
            let spans = if k == 0 { rows() } else { touched() };
            ring.push(
                k as f64 / fps,
                ((W, H), false),
                &spans,
                &bytes_of(&f, &spans),
            );
        }
        let kept = Kept::of(&ring);
        let frames: Vec<(f64, Vec<u8>)> = kept.frames().collect();
        // 14.98 s pushed: the frames from 4.98 s on, 501 of them.
        assert_eq!(frames.len(), (SPAN * fps) as usize + 1);
        for (t, f) in &frames {
            let k = (t * fps).round() as usize;
            assert!((t - k as f64 / fps).abs() < 1e-9);
            assert!(*f == frame(k), "frame {k}");
        }
        assert_eq!(frames[0].0, 4.98);
    }

    #[test]
    fn bgra_frames_and_frames_of_many_changes_come_back_as_shown() {
        // 400x200, every pixel changing each frame: deflated, BGRA.
        let (w, h) = (400u32, 200u32);
        let pic = |k: u32| -> Vec<u8> {
            (0..w * h)
                .flat_map(|i| [(i + k) as u8, (i * 3 + k) as u8, (i / 400) as u8, 255])
                .collect()
        };
        let bgra = |f: &[u8]| -> Vec<u8> {
            f.chunks_exact(4)
                .flat_map(|p| [p[2], p[1], p[0], p[3]])
                .collect()
        };
        let all: Vec<Span> = (0..h).map(|y| Span { y, x0: 0, x1: w }).collect();
        let mut ring = Ring::default();
        for k in 0..5 {
            ring.push(f64::from(k) / 30.0, ((w, h), true), &all, &bgra(&pic(k)));
        }
        let kept = Kept::of(&ring);
        assert!(kept.segments[0].deltas.iter().all(|d| d.deflated));
        let frames: Vec<(f64, Vec<u8>)> = kept.frames().collect();
        assert_eq!(frames.len(), 5);
        for (k, (_, f)) in frames.iter().enumerate() {
            assert!(*f == pic(k as u32), "frame {k}");
        }
    }

    /// A saved replay's frame count and length, read back from its file.
    pub(in crate::app::replay) fn animation_frames(path: &std::path::Path) -> u32 {
        let file = std::io::BufReader::new(std::fs::File::open(path).expect("written"));
        let reader = png::Decoder::new(file).read_info().expect("a PNG");
        reader
            .info()
            .animation_control
            .expect("animated")
            .num_frames
    }

    fn kept_with_clicks(clicks: Vec<Click>) -> Kept {
        let mut ring = Ring::default();
        for k in 0..100 {
            let f = frame(k);
            ring.push(k as f64 / 50.0, ((W, H), false), &rows(), &f);
        }
        ring.clicks = clicks;
        Kept::of(&ring)
    }

    #[test]
    fn a_save_writes_every_kept_frame_and_the_clicks_beside_them() {
        let dir = std::env::temp_dir().join(format!("nc-replay-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let timbre = Timbre::new(2e11, 0.29, 0.02, 0.26);
        let click = Click {
            at: 1.0,
            level: 0.5,
            pulse: 1e-4,
            pan: 0.0,
        };
        let png = dir.join("a.png");
        let saved = kept_with_clicks(vec![click])
            .write(&png, timbre)
            .expect("saved");
        assert_eq!(saved.frames, 100);
        assert_eq!(animation_frames(&png), 100);
        // 100 frames 20 ms apart: 2 s, the last shown as long as the others.
        assert!((saved.seconds - 2.0).abs() < 1e-9, "{}", saved.seconds);
        let wav = saved.wav.expect("a click was heard");
        assert_eq!(wav, dir.join("a.wav"));
        let reader = hound::WavReader::open(&wav).expect("a WAV");
        assert_eq!(reader.duration(), 96_000, "2 s at 48 kHz");
        // No click heard: no WAV.
        let silent = kept_with_clicks(Vec::new())
            .write(&dir.join("b.png"), timbre)
            .expect("saved");
        assert_eq!(silent.wav, None);
        assert!(!dir.join("b.wav").exists());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn nothing_kept_is_said_not_written() {
        let kept = Kept::of(&Ring::default());
        let path = std::env::temp_dir().join("nc-replay-none.png");
        let e = kept
            .write(&path, Timbre::new(2e11, 0.29, 0.02, 0.26))
            .expect_err("nothing to save");
        assert!(e.contains("nothing to save"), "{e}");
        assert!(!path.exists());
    }
}
