//! Writing pictures and sound: PNG frames, animated GIFs and PNGs, SVG plots
//! and WAV soundtracks (`file`: every one atomically, and never over a file of
//! the user's). The last stage of the data flow without a window.

mod animated_gif;
mod animated_png;
mod animation;
mod encode;
mod file;

pub use animated_gif::GifWriter;
pub use animated_png::ApngWriter;
pub use animation::Delays;
pub use encode::{write_png, write_wav};
pub use file::{AtomicFile, Kind, WriteError, check_output, clean_up_on_interrupt, write_all};
