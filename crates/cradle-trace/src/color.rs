//! The tracer's output: linear colour to sRGB bytes (pixels' texture is
//! `Rgba8UnormSrgb`, PNGs are sRGB) and the RGBA8 [`Image`] the renderers fill.

/// An RGBA8 picture, sRGB-encoded, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height * 4` bytes.
    pub rgba: Vec<u8>,
}

/// `THRESHOLDS[b]` is the linear value at which the sRGB byte becomes `b + 1`: the
/// decoded midpoint `(b + 0.5) / 255`, computed in f64 once.
fn thresholds() -> &'static [f32; 255] {
    static T: std::sync::OnceLock<[f32; 255]> = std::sync::OnceLock::new();
    T.get_or_init(|| {
        std::array::from_fn(|b| {
            let s = (b as f64 + 0.5) / 255.0;
            let linear = if s <= 0.040_45 {
                s / 12.92
            } else {
                ((s + 0.055) / 1.055).powf(2.4)
            };
            linear as f32
        })
    })
}

/// Linear [0, 1] to an sRGB byte (IEC 61966-2-1), rounded to the nearest byte and
/// clamping out-of-range values: the count of decision points at or below the
/// value, found by binary search instead of a `powf` per channel.
#[must_use]
pub fn srgb8(linear: f32) -> u8 {
    // NaN counts as 0, like the clamp it replaces.
    thresholds().partition_point(|&t| t <= linear) as u8
}
