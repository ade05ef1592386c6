//! Where in a pixel its rays go: the sub-pixel sample offsets shared by uniform
//! and adaptive anti-aliasing (adaptive adds more samples only at edges).

/// Sub-pixel sample offsets: the pixel centre for one sample, else the first `n`
/// points of the R2 low-discrepancy sequence (the same for every pixel).
#[must_use]
pub fn sample_offsets(n: u32) -> Vec<(f32, f32)> {
    // Roberts' R2: steps by the inverse powers of the plastic number.
    const A1: f64 = 0.754_877_666_246_692_7;
    const A2: f64 = 0.569_840_290_998_053_3;
    if n <= 1 {
        return vec![(0.5, 0.5)];
    }
    (0..n)
        .map(|i| {
            (
                ((0.5 + A1 * f64::from(i)) % 1.0) as f32,
                ((0.5 + A2 * f64::from(i)) % 1.0) as f32,
            )
        })
        .collect()
}
