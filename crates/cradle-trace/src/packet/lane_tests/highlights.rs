//! The Phong highlight's powers over the lanes (portable and AVX2 builds)
//! against the scalar ones, and where the highlight is cut.

use super::super::vec::F8;
use super::Lcg;
use crate::simd::{Portable, Simd};
/// `x^n` by `powi` over lanes of build `s`.
fn powi_lanes<S: Simd>(s: S, x: &F8, n: u32) -> F8 {
    S::store(crate::material::powi(s.load(x), n))
}

#[test]
fn whole_exponents_are_powers_by_squaring_in_every_build() {
    use crate::material::{Phong, highlight, powi, whole};
    assert_eq!(
        [0.0, 0.5, 1.0, 120.0, 120.5, 10_000.0, 10_001.0, f32::NAN].map(whole),
        [
            None,
            None,
            Some(1),
            Some(120),
            None,
            Some(10_000),
            None,
            None
        ]
    );
    let mut rng = Lcg(17);
    for n in [1, 2, 3, 7, 20, 40, 120, 1000, 4097, 10_000] {
        for _ in 0..50 {
            let x: F8 = std::array::from_fn(|_| rng.f().abs());
            for got in each_build!(|s| powi_lanes(s, &x, n)) {
                for (g, &x) in got.iter().zip(&x) {
                    // Lanes: the scalar bits.
                    assert_eq!(g.to_bits(), powi(x, n).to_bits(), "{x}^{n}");
                    // Against f64: each squaring at most doubles the relative
                    // error and adds one rounding, so below n roundings of
                    // 2^-24 (plus the smallest normal, for underflow).
                    let want = f64::from(x).powi(n as i32);
                    let tol = f64::from(n) * 2f64.powi(-24) * want + 1.2e-38;
                    assert!(
                        (f64::from(*g) - want).abs() <= tol,
                        "{x}^{n}: {g} vs {want}"
                    );
                }
            }
        }
    }
    assert_eq!(highlight(0.5, Phong::new(2.5)), 0.5f32.powf(2.5));
}

/// A highlight is 0 below the least `facing` kept, whose power is 2^-100
/// (within 0.2%: `least` is rounded to `f32`, an error of at most 2^-24 that
/// the exponent multiplies, up to 10,000 times, so at most 0.06%); from
/// `least` up it is the power, a normal number, so no squaring before it met a
/// subnormal one (each is at least the result, `facing` being at most 1).
#[test]
fn highlights_below_2_to_the_minus_100_are_cut() {
    use crate::material::{Phong, highlight, powi};
    for e in [
        1.0, 2.0, 2.5, 7.0, 20.0, 40.0, 120.0, 1000.0, 4097.0, 10_000.0,
    ] {
        let phong = Phong::new(e);
        let least = phong.least;
        let ratio = f64::from(least).powf(f64::from(e)) / 2f64.powi(-100);
        assert!(
            (ratio - 1.0).abs() < 2e-3,
            "{e}: least^e is {ratio} x 2^-100"
        );
        let below = f32::from_bits(least.to_bits() - 1);
        assert_eq!(highlight(below, phong), 0.0, "{e}");
        assert_eq!(highlight(0.0, phong), 0.0, "{e}");
        let kept = highlight(least, phong);
        assert!(kept.is_normal() && kept >= 2f32.powi(-101), "{e}: {kept}");
        if let Some(n) = phong.whole {
            assert_eq!(kept.to_bits(), powi(least, n).to_bits(), "{e}");
            assert_eq!(highlight(0.75, phong).to_bits(), powi(0.75f32, n).to_bits());
        }
    }
}
