//! The elliptic functions against independent high-precision values (mpmath 1.3 at
//! 30 digits, `mp.ellipfun`, `mp.ellipk`, `mp.ellipf`) and the period table.

#![expect(
    clippy::unreadable_literal,
    reason = "reference values as mpmath prints them, digit for digit"
)]
#![expect(
    clippy::excessive_precision,
    reason = "reference values are quoted with every digit mpmath printed"
)]

use cradle_physics::elliptic::{ellip_f, ellip_k, phase_of, sncndn};
use cradle_physics::period_ratio;

/// Double precision carries ~16 digits; the Landen recursion and range reduction
/// lose up to a few ulps per step, and u = 10 near m = 1 is reduced by ~3 periods:
/// 2e-14 absolute leaves room for that and nothing more.
const TOL: f64 = 2e-14;

#[test]
fn sn_cn_dn_match_mpmath() {
    let cases = [
        (
            0.3,
            0.5,
            [
                0.29341273316845537748,
                0.95598586182778707744,
                0.97824050417436120533,
            ],
        ),
        (
            1.7,
            0.9,
            [
                0.95223054210801865053,
                0.3053800823181972353,
                0.42887211987841085076,
            ],
        ),
        (
            -2.5,
            0.25,
            [
                -0.74990304990178414367,
                -0.66154774260668612792,
                0.92704441853505625866,
            ],
        ),
        (
            10.0,
            0.99,
            [
                -0.99142074486068204993,
                -0.13070924473766339791,
                0.16405504440062637568,
            ],
        ),
        (
            0.8,
            0.999999,
            [
                0.66403682446600728062,
                0.74769987010370747731,
                0.74770016497123049264,
            ],
        ),
    ];
    for (u, m, want) in cases {
        let (sn, cn, dn) = sncndn(u, m);
        for (got, want, name) in [
            (sn, want[0], "sn"),
            (cn, want[1], "cn"),
            (dn, want[2], "dn"),
        ] {
            assert!(
                (got - want).abs() < TOL,
                "{name}({u}, {m}) = {got}, mpmath {want}"
            );
        }
    }
}

#[test]
fn complete_integral_matches_mpmath() {
    for (m, want) in [
        (0.5, 1.8540746773013719184),
        (0.99, 3.6956373629898742386),
        (0.999999999, 11.747927296421043878),
    ] {
        let got = ellip_k(m);
        // Relative: K grows like ln(4/k') near m = 1, each digit still counts.
        assert!(
            (got - want).abs() < 1e-14 * want,
            "K({m}) = {got}, mpmath {want}"
        );
    }
    assert_eq!(ellip_k(0.0), std::f64::consts::FRAC_PI_2);
}

#[test]
fn incomplete_integral_matches_mpmath_and_inverts_sn() {
    for (phi, m, want) in [
        (0.7, 0.5, 0.72877030571819021448),
        (1.5, 0.99, 3.036014097339709753),
        (-1.2, 0.3, -1.2748327603866130484),
        (4.0, 0.8, 5.467873527678046577),
    ] {
        let got = ellip_f(phi, m);
        assert!(
            (got - want).abs() < 1e-14 * want.abs(),
            "F({phi}|{m}) = {got}, mpmath {want}"
        );
    }
    // phase_of is the inverse of (sn, cn) over a whole period.
    for i in -20..20 {
        let u = f64::from(i) * 0.17;
        let m = 0.7;
        let (sn, cn, _) = sncndn(u, m);
        let back = phase_of(sn, cn, m);
        let (sn2, cn2, _) = sncndn(back, m);
        assert!(
            (sn2 - sn).abs() < TOL && (cn2 - cn).abs() < TOL,
            "u = {u}: phase {back}"
        );
    }
}

#[test]
fn limits_are_sin_and_tanh() {
    for u in [-3.0, -0.5, 0.0, 0.25, 2.0] {
        let (sn, cn, dn) = sncndn(u, 0.0);
        assert_eq!((sn, cn, dn), (f64::sin(u), f64::cos(u), 1.0));
        let (sn, cn, _) = sncndn(u, 1.0);
        assert!((sn - f64::tanh(u)).abs() < 1e-15 && (cn - 1.0 / f64::cosh(u)).abs() < 1e-15);
    }
}

#[test]
fn large_amplitude_period_ratios_match_the_table() {
    // T/T0 = 2K(k)/pi, k = sin(amplitude/2); the table, to its 10 decimals.
    let table = [
        (10.0, 1.0019071881),
        (30.0, 1.0174087976),
        (60.0, 1.0731820071),
        (90.0, 1.1803405990),
        (120.0, 1.3728805006),
        (150.0, 1.7622037295),
        (170.0, 2.4393627197),
        (179.0, 3.9010651604),
    ];
    for (deg, want) in table {
        let got = period_ratio(f64::to_radians(deg));
        // The table is rounded to 10 decimals: half a unit of the last place.
        assert!((got - want).abs() <= 0.5e-10, "{deg} deg: {got} vs {want}");
    }
}
