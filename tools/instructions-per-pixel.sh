#!/usr/bin/env bash
# Instructions per pixel of a full frame, counted by callgrind: independent of the
# machine's load, so it judges a change to the tracer where timings are noise.
#
#   tools/instructions-per-pixel.sh [BENCH RENDER FLAGS...]
#
# Runs `bench render --threads 1 --mode full --width 600 --height 300` with
# --frames 3 and with --frames 1 under callgrind and divides the difference by 2
# frames and 180,000 pixels, so start-up and warm-up frames cancel out. Extra flags
# (say `--balls 200 --lift 10`) go to both runs. One sample per pixel (the packet
# tracer's measure) unless the flags give `--samples`. Needs valgrind; uses
# target/release/newtons-cradle (or $BIN), building it first when missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${BIN:-$root/target/release/newtons-cradle}"
command -v valgrind >/dev/null || { echo "needs valgrind (apt-get install valgrind)" >&2; exit 1; }
[ -x "$bin" ] || cargo build --release --quiet --manifest-path "$root/Cargo.toml"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
count() {
  valgrind --tool=callgrind --callgrind-out-file="$out/cg.$1" "$bin" bench render \
    --threads 1 --mode full --frames "$1" --width 600 --height 300 "${@:2}" \
    >/dev/null 2>"$out/log.$1"
  grep -o "Collected : [0-9]*" "$out/log.$1" | awk '{print $3}'
}
extra=("$@")
[[ " $* " == *" --samples "* ]] || extra+=(--samples 1)
set -- "${extra[@]}"
one=$(count 1 "$@")
three=$(count 3 "$@")
awk -v a="$one" -v b="$three" 'BEGIN { printf "instructions per pixel: %.1f\n", (b - a) / 2 / 180000 }'
