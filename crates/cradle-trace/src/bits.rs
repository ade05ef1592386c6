//! A bit per pixel of a row (on the stack for rows up to 4,096 pixels), for the
//! incremental frames' per-row sets: the pixels the motion may have changed, those
//! to test or supersample again, found in any order and read back ascending.

/// Rows up to this many pixels keep their bits on the stack.
const ON_STACK: usize = 64 * 64;

/// Room for a row's bits: on the stack, or for a longer row on the heap.
#[derive(Debug)]
pub(crate) struct BitRoom {
    stack: [u64; ON_STACK / 64],
    heap: Vec<u64>,
}

impl BitRoom {
    /// Room, not yet used.
    pub(crate) fn new() -> Self {
        Self {
            stack: [0; ON_STACK / 64],
            heap: Vec::new(),
        }
    }

    /// The empty set of pixels `0..n`, in this room.
    pub(crate) fn row(&mut self, n: usize) -> RowBits<'_> {
        let words = n.div_ceil(64);
        if n <= ON_STACK {
            let w = &mut self.stack[..words];
            w.fill(0);
            RowBits(w)
        } else {
            self.heap.clear();
            self.heap.resize(words, 0);
            RowBits(&mut self.heap)
        }
    }
}

/// Into `out` (emptied first), the distinct pixels of `xs` (each below `n`),
/// ascending.
pub(crate) fn ascending(n: usize, xs: impl IntoIterator<Item = usize>, out: &mut Vec<usize>) {
    let mut room = BitRoom::new();
    let mut bits = room.row(n);
    for x in xs {
        bits.set(x);
    }
    out.clear();
    out.extend(bits.iter());
}

/// A set of pixels of a row, a bit each.
#[derive(Debug)]
pub(crate) struct RowBits<'a>(&'a mut [u64]);

impl RowBits<'_> {
    /// Adds pixel `k`.
    #[inline]
    pub(crate) fn set(&mut self, k: usize) {
        self.0[k / 64] |= 1 << (k % 64);
    }

    /// Whether pixel `k` is in the set.
    #[inline]
    pub(crate) fn has(&self, k: usize) -> bool {
        self.0[k / 64] >> (k % 64) & 1 != 0
    }

    /// How many pixels the set holds.
    #[cfg(test)]
    pub(crate) fn count(&self) -> usize {
        self.0.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// The pixels in the set, ascending.
    pub(crate) fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        let mut words = self.0.iter().enumerate();
        let mut cur = (0, 0u64);
        std::iter::from_fn(move || {
            while cur.1 == 0 {
                let (i, &w) = words.next()?;
                cur = (i, w);
            }
            let k = cur.0 * 64 + cur.1.trailing_zeros() as usize;
            cur.1 &= cur.1 - 1;
            Some(k)
        })
    }

    /// The pixels in the set as runs of pixels side by side, ascending.
    pub(crate) fn runs(&self) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
        let mut ks = self.iter().peekable();
        std::iter::from_fn(move || {
            let start = ks.next()?;
            let mut end = start + 1;
            while ks.next_if_eq(&end).is_some() {
                end += 1;
            }
            Some(start..end)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::{BitRoom, ascending};

    #[test]
    fn a_set_reads_back_sorted_without_repeats_on_both_sides_of_the_stack_limit() {
        // A buffer used before comes back with only the new set.
        let mut out = vec![7, 7, 7];
        ascending(10, [3, 1, 3, 9, 0, 1], &mut out);
        assert_eq!(out, vec![0, 1, 3, 9]);
        ascending(10, [], &mut out);
        assert!(out.is_empty());
        let mut room = BitRoom::new();
        for n in [1, 64, 4096, 4097, 10_000, 64] {
            let xs = [n - 1, 0, 63 % n, n / 2, n - 1, (n / 2 + 1) % n, 0];
            let mut want: Vec<usize> = xs.to_vec();
            want.sort_unstable();
            want.dedup();
            ascending(n, xs, &mut out);
            assert_eq!(out, want, "n = {n}");
            // Room used again starts empty.
            let mut bits = room.row(n);
            for x in xs {
                bits.set(x);
            }
            assert_eq!(bits.count(), want.len(), "n = {n}");
            assert!((0..n).all(|k| bits.has(k) == want.contains(&k)), "n = {n}");
        }
    }

    /// A set reads back as its runs of neighbours, across word boundaries,
    /// at both ends of the row, and empty as none.
    #[test]
    fn a_set_reads_back_as_runs_of_neighbours() {
        let mut room = BitRoom::new();
        let n = 200;
        let mut bits = room.row(n);
        assert_eq!(bits.runs().count(), 0);
        for k in [0, 1, 2, 5, 62, 63, 64, 65, 127, 130, 199] {
            bits.set(k);
        }
        let runs: Vec<_> = bits.runs().collect();
        assert_eq!(runs, vec![0..3, 5..6, 62..66, 127..128, 130..131, 199..200]);
    }
}
