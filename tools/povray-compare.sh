#!/usr/bin/env bash
# A full frame against POV-Ray 3.7 on the same frame, in one run on one machine.
#
#   tools/povray-compare.sh [RUNS] [THREADS]      (defaults: 5 runs, 2 threads)
#
# Writes the default asset's first timed `bench render` frame (t = 0.5 s) as a
# POV-Ray scene (examples/povray_scene.rs: the same shapes, lights, camera and
# mirror depth), then alternates RUNS times: POV-Ray at 1200x600 without
# anti-aliasing on THREADS threads, and `bench render --mode full --samples 1`
# (15 frames each run). Prints each run, then the medians and the median of the
# per-run ratios (the figure to quote: both sides of a ratio share the run's load).
# POV-Ray's figure is its own "Trace Time" (its ~0.7 s start-up and the PNG
# write excluded, which flatters it); ours is the median frame of the run.
# Needs povray (apt-get install povray); builds the release binary and example.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
runs="${1:-5}"
threads="${2:-2}"
command -v povray >/dev/null || { echo "needs povray (apt-get install povray)" >&2; exit 1; }
cd "$root"
cargo build --release --quiet --bin newtons-cradle --example povray_scene
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
target/release/examples/povray_scene > "$work/frame.pov"
pov_ms() {
  povray +I"$work/frame.pov" +O"$work/pov.png" +W1200 +H600 -A +WT"$threads" -D -V 2>&1 |
    tr '\r' '\n' | grep -A0 "Trace Time" | grep -o "([0-9.]* seconds)" | tr -d '(' |
    awk '{ printf "%.1f\n", $1 * 1000 }'
}
ours_ms() {
  target/release/newtons-cradle bench render --mode full --samples 1 --threads "$threads" \
    --frames 15 --json 2>/dev/null | grep -o '"ms_median":[0-9.]*' | cut -d: -f2
}
: > "$work/pov"
: > "$work/ours"
: > "$work/ratio"
for i in $(seq "$runs"); do
  p=$(pov_ms)
  o=$(ours_ms)
  echo "$p" >> "$work/pov"
  echo "$o" >> "$work/ours"
  echo "$p / $o" | bc -l >> "$work/ratio"
  printf "run %d: POV-Ray %8.1f ms   newtons-cradle %6.1f ms   ratio %5.1fx\n" \
    "$i" "$p" "$o" "$(echo "$p / $o" | bc -l)"
done
median() { sort -n "$1" | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
p=$(median "$work/pov")
o=$(median "$work/ours")
printf "medians (%d runs, %d threads, 1200x600, 1 sample): POV-Ray %.1f ms, newtons-cradle %.1f ms; median ratio %.1fx\n" \
  "$runs" "$threads" "$p" "$o" "$(median "$work/ratio")"
