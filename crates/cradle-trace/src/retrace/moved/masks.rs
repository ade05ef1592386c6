//! The motion filter's walk as bit masks: which units of a block or of a
//! super-block's blocks the screen's runs touch, which pixels' or blocks'
//! cells meet the moved ones (eight at a time in a lane build), and a block's
//! edge flags, each in the low bits of a `u32`.

use crate::motion::{BLOCK, Cells, SUPER};
use crate::simd::Simd;

// `flags`, `meeting` and `low_bits` hold a block (or a super-block's blocks)
// in the low bits of a `u32`, a block's flags in one `u64`.
const _: () = assert!(BLOCK == 1 << BLOCK_SHIFT && SUPER == 8 && SUPER * BLOCK == 1 << SUPER_SHIFT);
/// `BLOCK` as a shift, and the pixels of a super-block.
pub(super) const BLOCK_SHIFT: u32 = 3;
pub(super) const SUPER_SHIFT: u32 = 6;

/// Moves `r` on to the first of `runs` (ascending) that ends after pixel `x`.
#[inline(always)]
#[expect(
    clippy::inline_always,
    reason = "a few compares, inlined into each build"
)]
pub(super) fn skip_ended(runs: &[(u32, u32)], r: &mut usize, x: usize) {
    while *r < runs.len() && runs[*r].1 as usize <= x {
        *r += 1;
    }
}

/// The units of `1 << SHIFT` pixels of `xs` (at most eight units, from
/// `xs.start`) that `runs` (ascending, apart; the first ending after
/// `xs.start`) meet: bit `i` for the unit from `xs.start + (i << SHIFT)`.
#[inline(always)]
#[expect(
    clippy::inline_always,
    reason = "a few compares, inlined into each build"
)]
pub(super) fn run_bits<const SHIFT: u32>(runs: &[(u32, u32)], xs: &std::ops::Range<usize>) -> u32 {
    (runs.iter())
        .take_while(|run| (run.0 as usize) < xs.end)
        .fold(0, |m, &(a, b)| {
            let (a, b) = ((a as usize).max(xs.start), (b as usize).min(xs.end));
            let (a, b) = (a - xs.start, b - xs.start);
            m | (low_bits((b + (1 << SHIFT) - 1) >> SHIFT) & !low_bits(a >> SHIFT))
        })
}

/// Bit `i` set where `cells[i] & with` is not zero (at most eight sets):
/// eight at a time in lane build `s`.
#[inline(always)]
#[expect(
    clippy::inline_always,
    reason = "a few instructions, inlined into each build"
)]
pub(super) fn meeting<S: Simd>(s: S, cells: &[Cells], with: Cells) -> u32 {
    match <&[Cells; 8]>::try_from(cells) {
        Ok(eight) => u32::from(s.meeting(eight, with)),
        Err(_) => {
            (cells.iter().enumerate()).fold(0, |m, (i, &c)| m | u32::from(c & with != 0) << i)
        }
    }
}

/// The bits below bit `n` (`n` at most eight).
#[inline(always)]
#[expect(clippy::inline_always, reason = "a shift, inlined into each build")]
fn low_bits(n: usize) -> u32 {
    (1u32 << n) - 1
}

/// Bit `i` set where `is[i]` holds (at most [`BLOCK`] flags): a whole
/// block's eight bytes, each 0 or 1, gathered into the top byte of one
/// product (byte `i` of the multiplier's lands its bit at `56 + i`, and no
/// two partial products meet there).
#[inline(always)]
#[expect(clippy::inline_always, reason = "a product, inlined into each build")]
pub(super) fn flags(is: &[bool]) -> u32 {
    match <[bool; 8]>::try_from(is) {
        Ok(eight) => {
            let bytes = u64::from_le_bytes(eight.map(u8::from));
            (bytes.wrapping_mul(0x0102_0408_1020_4080) >> 56) as u32
        }
        Err(_) => (is.iter().enumerate()).fold(0, |m, (i, &f)| m | u32::from(f) << i),
    }
}

#[cfg(test)]
mod tests {
    use super::{meeting, run_bits};
    use crate::motion::Cells;
    use crate::simd::{Build, Kernel, Simd};

    /// A set meets another where they share a bit, in the low half, the
    /// high half or both, in every lane build, eight at a time and in a
    /// shorter last chunk.
    #[test]
    fn sets_of_cells_meet_where_they_share_a_bit() {
        struct Meet<'a>(&'a [Cells], Cells);
        impl Kernel for Meet<'_> {
            type Output = u32;
            fn run<S: Simd>(self, s: S) -> u32 {
                meeting(s, self.0, self.1)
            }
        }
        let with: Cells = 1 << 3 | 1 << 70;
        let sets: [Cells; 8] = [
            0,
            1 << 3,
            1 << 70,
            1 << 4 | 1 << 71,
            Cells::MAX,
            1 << 64,
            1 << 3 | 1 << 70,
            !with,
        ];
        for build in Build::all() {
            assert_eq!(build.run(Meet(&sets, with)), 0b0101_0110, "{build:?}");
            assert_eq!(build.run(Meet(&sets[..5], with)), 0b1_0110, "{build:?}");
            assert_eq!(build.run(Meet(&sets, 0)), 0, "{build:?}");
        }
    }

    /// Runs mark the pixels they hold, and the blocks of eight they touch,
    /// from the block's or super-block's first pixel, clipped to it (the
    /// runs given start with the first that ends after that pixel).
    #[test]
    fn runs_mark_the_pixels_and_blocks_they_touch() {
        let runs = [(3, 5), (7, 9), (12, 30)];
        assert_eq!(run_bits::<0>(&runs, &(0..8)), 0b1001_1000);
        assert_eq!(run_bits::<0>(&runs[1..], &(8..16)), 0b1111_0001);
        // A last block of four pixels.
        assert_eq!(run_bits::<0>(&runs[2..], &(24..28)), 0b1111);
        // Blocks of eight from pixel 0: 3..5 and 7..9 touch blocks 0 and 1,
        // 12..30 blocks 1 to 3; nothing touches block 4.
        assert_eq!(run_bits::<3>(&runs, &(0..64)), 0b1111);
        assert_eq!(run_bits::<3>(&[(40, 41)], &(0..64)), 0b10_0000);
        assert_eq!(run_bits::<3>(&[(64, 70)], &(0..64)), 0);
    }
}
