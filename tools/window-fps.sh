#!/usr/bin/env bash
# The frame rate of the real window, as a user sees it: runs the app at
# 1200x600 on a virtual display with software Vulkan (tests/window/with-display.sh),
# starts the swing, does what STATE says for 10 s, and prints the median of
# the fps the app logs every 2 s (the first line, the start, left out).
#
#   tools/window-fps.sh STATE [APP FLAGS...]
#
# STATE: swing (the swing alone), orbit (the right button held and the mouse
# circling, about 60 moves a second), panel (the control panel open, Tab),
# graphs (the graphs window open, G).
# With LOG=FILE the app's log is kept there (with RUST_LOG=info,frame_cost=trace
# it holds each frame's step, egui, upload and present costs on the main thread).
# Extra flags go to the app (say `--config assets/presets/realistic.ron` or
# `--balls 200 --lift 20`). Uses target/release/newtons-cradle (or $BIN).
# Prints `STATE: median N fps (lines: a b c ...; trace ms: ...)`, the trace
# times being the logged medians of each line's frames.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${BIN:-$root/target/release/newtons-cradle}"
[ -x "$bin" ] || cargo build --release --quiet --manifest-path "$root/Cargo.toml"
state="${1:?usage: window-fps.sh swing|orbit|panel|graphs [APP FLAGS...]}"
shift
case "$state" in swing|orbit|panel|graphs) ;; *) echo "STATE: swing, orbit, panel or graphs" >&2; exit 2 ;; esac
if [ -z "${DISPLAY:-}" ]; then
  exec "$root/tests/window/with-display.sh" "$0" "$state" "$@"
fi
# The app runs in a scratch folder (what it writes stays out of the tree), so
# flags that name files here are made absolute first.
args=()
for a in "$@"; do
  if [ -e "$a" ] && [[ "$a" != /* ]]; then args+=("$PWD/$a"); else args+=("$a"); fi
done
set -- "${args[@]}"
work="$(mktemp -d)"
trap 'kill "$pid" 2>/dev/null; rm -rf "$work"' EXIT
(cd "$work" && exec "$bin" --width 1200 --height 600 "$@") >"$work/app.log" 2>&1 &
pid=$!
wid=""
for _ in $(seq 1 150); do
  wid=$(xdotool search --name "Newton's cradle" 2>/dev/null | head -n 1) && [ -n "$wid" ] && break
  sleep 0.2
done
[ -n "$wid" ] || { echo "no window" >&2; cat "$work/app.log" >&2; exit 1; }
xdotool windowfocus --sync "$wid" 2>/dev/null || true
sleep 2
# The assets start paused: Space runs the swing.
xdotool key space
[ "$state" = panel ] && xdotool key Tab
[ "$state" = graphs ] && xdotool key g
end=$((SECONDS + 11))
if [ "$state" = orbit ]; then
  xdotool mousemove --window "$wid" 600 300 mousedown 3
  # A slow circle of 40 px: the view turns one way, then back.
  python3 -c "import math
for i in range(2000): print(int(600 + 40 * math.cos(i / 20)), int(300 + 40 * math.sin(i / 20)))" >"$work/path"
  while read -r x y && [ $SECONDS -lt $end ]; do
    xdotool mousemove --window "$wid" "$x" "$y"
    sleep 0.016
  done <"$work/path"
  xdotool mouseup 3
else
  sleep 11
fi
xdotool key Escape
for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
[ -n "${LOG:-}" ] && cp "$work/app.log" "$LOG"
fps=$(grep -o "[0-9.]* fps, trace" "$work/app.log" | awk '{print $1}' | tail -n +2)
[ -n "$fps" ] || { echo "$state: no fps logged" >&2; tail -5 "$work/app.log" >&2; exit 1; }
median=$(echo "$fps" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
trace=$(grep -o "fps, trace [0-9.]* ms" "$work/app.log" | awk '{print $3}' | tail -n +2 | tr '\n' ' ')
echo "$state: median $median fps (lines: $(echo $fps | tr '\n' ' '); trace ms: $trace)"
