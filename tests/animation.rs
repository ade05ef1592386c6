//! The animations `render` writes: an animated PNG whose frames, decoded, are
//! the PNG sequence's byte for byte while storing only what changed, and a GIF
//! of changed rectangles on one palette that stays close to the sequence and
//! small.

mod common;

use newtons_cradle::config::Config;
use newtons_cradle::headless::{Output, render};
use std::path::Path;

/// The default cradle at `width` x `height`.
fn config(width: u32, height: u32) -> Config {
    let mut c = Config::default();
    c.render.width = width;
    c.render.height = height;
    c
}

/// The RGBA8 pixels of a PNG file.
fn png_pixels(path: &Path) -> Vec<u8> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    buf
}

/// Every frame of an animated PNG as shown: each frame's rectangle put over
/// the canvas (replacing with blend "source", over it with "over"), the
/// canvas kept between frames (dispose "none", all this writer uses).
fn apng_frames(path: &Path) -> Vec<Vec<u8>> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let (w, h) = reader.info().size();
    let frames = reader
        .info()
        .animation_control
        .expect("animated")
        .num_frames;
    let mut canvas = vec![0u8; (w * h * 4) as usize];
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let mut out = Vec::new();
    for _ in 0..frames {
        let info = reader.next_frame(&mut buf).unwrap();
        let fc = reader
            .info()
            .frame_control
            .expect("a frame control per frame");
        assert_eq!(fc.dispose_op, png::DisposeOp::None);
        for y in 0..fc.height {
            for x in 0..fc.width {
                let src = (y as usize * info.line_size) + x as usize * 4;
                let px = &buf[src..src + 4];
                let dst = (((fc.y_offset + y) * w + fc.x_offset + x) * 4) as usize;
                match fc.blend_op {
                    png::BlendOp::Source => canvas[dst..dst + 4].copy_from_slice(px),
                    png::BlendOp::Over => {
                        // Opaque frames: a pixel is either kept or replaced.
                        assert!(px[3] == 0 || px[3] == 255, "alpha {}", px[3]);
                        if px[3] == 255 {
                            canvas[dst..dst + 4].copy_from_slice(px);
                        }
                    }
                }
            }
        }
        out.push(canvas.clone());
    }
    out
}

/// The same frames stored whole as an animated PNG (every frame the full
/// picture), written here with the `png` crate: what the changed rectangles
/// are measured against.
fn whole_apng_size(frames: &[Vec<u8>], w: u32, h: u32) -> usize {
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, w, h);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_animated(frames.len() as u32, 0).unwrap();
        let mut writer = enc.write_header().unwrap();
        for f in frames {
            writer.set_frame_delay(1, 30).unwrap();
            writer.write_image_data(f).unwrap();
        }
        writer.finish().unwrap();
    }
    bytes.len()
}

/// Renders `output` (the default cradle at 600x300, 60 frames at 30 fps, into
/// `dir`) and the same frames as a PNG sequence; returns the sequence's pixels.
fn render_beside_sequence(dir: &Path, output: &Output) -> Vec<Vec<u8>> {
    let c = config(600, 300);
    render(&c, 0.0, output, None, None).expect("renders");
    let seq = dir.join("seq");
    let sequence = Output::Sequence {
        dir: seq.clone(),
        first: 0,
        frames: 60,
        fps: 30.0,
    };
    render(&c, 0.0, &sequence, None, None).expect("renders");
    (0..60)
        .map(|n| png_pixels(&seq.join(format!("frame_{n:04}.png"))))
        .collect()
}

#[test]
fn an_animated_png_shows_the_sequence_byte_for_byte_in_a_third_of_the_bytes() {
    let dir = common::temp_dir("apng");
    let apng = dir.join("cradle.png");
    let output = Output::Apng {
        path: apng.clone(),
        frames: 60,
        fps: 30.0,
    };
    let want = render_beside_sequence(&dir, &output);
    let shown = apng_frames(&apng);
    assert_eq!(shown.len(), 60);
    for (n, (got, want)) in shown.iter().zip(&want).enumerate() {
        assert!(got == want, "frame {n} differs from the sequence's");
    }
    let size = std::fs::metadata(&apng).unwrap().len() as usize;
    let whole = whole_apng_size(&want, 600, 300);
    assert!(3 * size <= whole, "{size} bytes against {whole} whole");
    std::fs::remove_dir_all(&dir).ok();
}

/// Every frame of a GIF as shown, RGB: each frame's rectangle over the
/// canvas, its transparent pixels keeping what was there.
fn gif_frames(path: &Path) -> Vec<Vec<u8>> {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(path).unwrap())
        .unwrap();
    let (w, h) = (decoder.width() as usize, decoder.height() as usize);
    let mut canvas = vec![0u8; w * h * 3];
    let mut out = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!(frame.dispose, gif::DisposalMethod::Keep);
        let (fw, fh) = (usize::from(frame.width), usize::from(frame.height));
        for y in 0..fh {
            for x in 0..fw {
                let px = &frame.buffer[(y * fw + x) * 4..(y * fw + x) * 4 + 4];
                if px[3] == 0 {
                    continue;
                }
                let at = ((usize::from(frame.top) + y) * w + usize::from(frame.left) + x) * 3;
                canvas[at..at + 3].copy_from_slice(&px[..3]);
            }
        }
        out.push(canvas.clone());
    }
    out
}

#[test]
fn a_gif_stores_changed_rectangles_on_one_palette_close_to_the_sequence() {
    let dir = common::temp_dir("gif-rects");
    let gif = dir.join("cradle.gif");
    let output = Output::Gif {
        path: gif.clone(),
        frames: 60,
        fps: 30.0,
    };
    let sequence = render_beside_sequence(&dir, &output);
    let shown = gif_frames(&gif);
    assert_eq!(shown.len(), 60);
    for (n, (got, want)) in shown.iter().zip(&sequence).enumerate() {
        let rgb: Vec<u8> = want
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        // 255 colours for a picture of smooth shading: PSNR above 40 dB is
        // beyond what the eye tells apart in a moving picture (measured: 49).
        let se: f64 = got
            .iter()
            .zip(&rgb)
            .map(|(&a, &b)| (f64::from(a) - f64::from(b)).powi(2))
            .sum();
        let psnr = 10.0 * (255.0f64.powi(2) * got.len() as f64 / se.max(1e-9)).log10();
        assert!(psnr > 40.0, "frame {n}: {psnr:.1} dB");
    }
    // The README's GIF (600x300, 60 frames): at most 1 MB.
    let size = std::fs::metadata(&gif).unwrap().len();
    assert!(size <= 1_000_000, "{size} bytes");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_apng_flag_is_checked_like_the_other_outputs() {
    let dir = common::temp_dir("apng-flags");
    let small = ["render", "--width", "32", "--height", "16"];
    let run = |more: &[&str]| common::run_in(&dir, &[&small[..], more].concat());
    let o = run(&["--apng", "a.png", "--gif", "b.gif"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("either --gif or --apng"));
    let o = run(&["--apng", "a.gif"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("allowed: a .png file name"));
    let o = run(&["--apng", "a.png", "--out", "b.png"]);
    assert_eq!(o.status.code(), Some(2));
    // A file of the user's that is not a PNG is never replaced.
    std::fs::write(dir.join("notes.png"), "my notes").unwrap();
    let o = run(&["--apng", "notes.png", "--frames", "2"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read(dir.join("notes.png")).unwrap(), b"my notes");
    // With its soundtrack, as a GIF takes one.
    let o = run(&["--apng", "a.png", "--frames", "3", "--audio", "a.wav"]);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    assert_eq!(apng_frames(&dir.join("a.png")).len(), 3);
    assert!(dir.join("a.wav").is_file());
    std::fs::remove_dir_all(&dir).ok();
}
