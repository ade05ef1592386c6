//! The stability stress suite at the size `cargo test` affords (a few CPU seconds):
//! 1e6 ideal impacts, 179.9 degree lifts with N = 1, 2 and 200, gaps, restitution
//! 0 and 0.5, tiny and huge cradles, Hertz contact, viscoelastic contact with air
//! drag. Each scenario's limits are in
//! `src/bench/stress.rs`; `newtons-cradle bench stress` runs them longer.

use newtons_cradle::bench::stress::{run, scenarios};

#[test]
fn every_stress_scenario_stays_within_its_limits() {
    let mut failures = Vec::new();
    let mut impacts = 0;
    for s in scenarios(1.0) {
        let r = run(&s);
        println!(
            "{}",
            serde_json::to_string(&r).expect("a report serializes")
        );
        // At this scale every run reaches its first strike and its rest time.
        if s.first_strike_energy.is_some() {
            assert!(
                r.first_strike_energy.is_finite(),
                "{}: no first strike",
                s.name
            );
        }
        if let Some(t) = s.rest_by {
            assert!(s.duration > t, "{}: shorter than its rest time", s.name);
        }
        impacts = impacts.max(r.impacts);
        failures.extend(
            r.failures(&s)
                .into_iter()
                .map(|f| format!("{}: {f}", s.name)),
        );
    }
    assert!(failures.is_empty(), "{failures:#?}");
    // The 10^6 impacts in one run.
    assert!(impacts >= 1_000_000, "largest run had {impacts} impacts");
}
