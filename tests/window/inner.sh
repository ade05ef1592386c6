#!/usr/bin/env bash
# Drives the real window (needs DISPLAY, xdotool, ImageMagick, python3): it
# draws a non-blank picture, a left-drag lifts a ball and release swings it,
# quick arrows keep it running, Space pauses, the window shows the framebuffer
# pixel for pixel, the wheel and drags change the view, Tab shows the control
# panel and the keys still work with it open, S while paused shows a notice, a
# preset loads and Ctrl+Z undoes it, 45 rapid resizes do not hang it, a saved
# config reloads and a bad one keeps the scene, S saves unique screenshots,
# Escape exits 0, a window destroyed from outside exits 0, and heavy settings
# (200 balls of the realistic cradle, 4K at 64 samples) still answer Escape;
# and the sound (sound.sh): clicks at the swing's rhythm, silence when muted,
# a silent window without a server; and the graphs (graphs.sh): G opens them,
# Shift+G saves a CSV; and V (replay.sh): the last 10 s as an animated PNG and
# a WAV.
set -uo pipefail
bin="$1"
work="$(mktemp -d)"
# One client connected throughout, so that Xvfb does not reset (and refuse the
# next start of the app) when the app is its last client and exits.
python3 "$(dirname "$0")/hold_display.py" &
holder=$!
trap 'kill "$pid" "$holder" 2>/dev/null; rm -rf "$work"' EXIT
pass=0; fail=0
ok() { echo "ok - $1"; pass=$((pass + 1)); }
bad() { echo "FAIL - $1"; fail=$((fail + 1)); }
shot() { import -window root "$work/$1.png"; }
differ() { compare -metric AE "$work/$1.png" "$work/$2.png" null: 2>&1 | cut -d' ' -f1; }
# The app's window id, once it is mapped (empty after 30 s).
find_window() {
  for _ in $(seq 1 150); do
    xdotool search --name "Newton's cradle" 2>/dev/null | head -n 1 | grep . && return
    sleep 0.2
  done
}
# Sets code to the exit code of the app ($pid) within 5 s (empty while it still
# runs); not in a subshell, which could not wait for it.
wait_exit() {
  code=""
  for _ in $(seq 1 50); do
    if ! kill -0 "$pid" 2>/dev/null; then wait "$pid"; code=$?; return; fi
    sleep 0.1
  done
}

cp "$(dirname "$bin")/../../assets/cradle.ron" "$work/cradle.ron"
cd "$work"
"$bin" --config "$work/cradle.ron" --width 480 --height 240 > "$work/app.log" 2>&1 &
pid=$!

wid=$(find_window)
if [ -z "$wid" ]; then bad "window appears"; cat "$work/app.log"; echo "0 passed, 1 failed"; exit 1; fi
ok "window appears"
xdotool windowfocus --sync "$wid" 2>/dev/null || xdotool windowfocus "$wid"
sleep 2

shot start
colors=$(identify -format %k "$work/start.png")
[ "$colors" -gt 200 ] && ok "draws a picture ($colors colours)" || bad "draws a picture ($colors colours)"

# Left-drag the right-end ball (at this size and the asset's view it sits at
# 284,132) out and up: it follows while held, and swings once let go.
xdotool mousemove --window "$wid" 284 132; sleep 0.3; xdotool mousedown 1; sleep 0.3
for x in 300 310 320 330 340 350 360; do xdotool mousemove --window "$wid" $x $((132 - (x - 284) / 2)); sleep 0.1; done
sleep 1; shot held1; sleep 0.5; shot held2
d1=$(differ start held1); d2=$(differ held1 held2)
grep -q "picked ball 5" "$work/app.log" && [ "$d1" != "0" ] && [ "$d2" = "0" ] \
  && ok "a left-drag lifts the right-end ball ($d1 pixels changed)" || bad "a left-drag lifts the right-end ball ($d1, $d2)"
xdotool mouseup 1; sleep 1.0; shot run1; sleep 1.0; shot run2
d=$(differ run1 run2)
[ "$d" != "0" ] && ok "let go, it swings ($d pixels changed)" || bad "let go, it swings"

# Quick arrow presses restart the swing from the start, still running.
xdotool key Up Down Right Left; sleep 1.0; shot run1; sleep 1.0; shot run2
d=$(differ run1 run2)
[ "$d" != "0" ] && ok "quick arrow presses keep it running ($d pixels changed)" || bad "quick arrow presses keep it running"
line=$(grep -o "[0-9.]* fps, trace [0-9.]* ms" "$work/app.log" | tail -n 1)
[ -n "$line" ] && ok "logs its frame rate while running ($line)" || bad "logs its frame rate while running"

xdotool key space; sleep 1.5; shot pause1; sleep 1.0; shot pause2
d=$(differ pause1 pause2)
[ "$d" = "0" ] && ok "still while paused" || bad "still while paused ($d pixels changed)"
# What the window shows is the framebuffer, pixel for pixel, after a run of
# incremental frames: the window against S's screenshot of the framebuffer.
import -window "$wid" "$work/window.png"; xdotool key s; sleep 1
first=$(ls "$work"/newtons-cradle-*.png 2>/dev/null | head -n 1)
d=$([ -n "$first" ] && compare -metric AE "$work/window.png" "$first" null: 2>&1 | cut -d' ' -f1)
[ "$d" = "0" ] && ok "the window shows the framebuffer" || bad "the window shows the framebuffer (${d:-no screenshot} pixels differ)"
# The notice goes before the view's checks below.
sleep 4

# Paused, the picture only changes when the view does: the wheel, a right-drag.
xdotool mousemove --window "$wid" 240 120 click 4 click 4; sleep 1.5; shot zoomed
d=$(differ pause2 zoomed)
[ "$d" != "0" ] && ok "the wheel zooms ($d pixels changed)" || bad "the wheel zooms"
xdotool mousemove --window "$wid" 200 120 mousedown 3 mousemove --window "$wid" 260 110 \
  mousemove --window "$wid" 300 100 mouseup 3; sleep 1.5; shot turned
d=$(differ zoomed turned)
[ "$d" != "0" ] && ok "a right-drag turns the view ($d pixels changed)" || bad "a right-drag turns the view"
xdotool key c; sleep 1

# Tab shows the control panel over the picture, and hides it again.
shot nopanel; xdotool key Tab; sleep 1.5; shot panel; xdotool key Tab; sleep 1.5; shot nopanel2
d1=$(differ nopanel panel); d2=$(differ nopanel nopanel2)
[ "$d1" != "0" ] && [ "$d2" = "0" ] && ok "Tab shows the control panel and hides it ($d1 pixels)" \
  || bad "Tab shows the control panel and hides it ($d1, $d2)"

# With the panel open the keys are still the app's: Space runs and stops the
# swing, H shows the help, arrows change the cradle and nothing is typed into
# the panel's fields (a blanked field would be refused: "not applied").
xdotool key Tab; sleep 1.5
xdotool key space; sleep 1; shot open1; sleep 0.7; shot open2
d=$(differ open1 open2)
[ "$d" != "0" ] && ok "Space runs the swing with the panel open ($d pixels changed)" \
  || bad "Space runs the swing with the panel open"
xdotool key space; sleep 1; shot open3; xdotool key h; sleep 1; shot open4; xdotool key h h; sleep 0.5
d=$(differ open3 open4)
[ "$d" != "0" ] && ok "H shows the help with the panel open ($d pixels changed)" \
  || bad "H shows the help with the panel open"
xdotool key Tab Tab Right Left; sleep 1
grep -q "not applied" "$work/app.log" && bad "keys are not typed into the panel" || ok "keys are not typed into the panel"
# S while paused: a notice with the file's name, gone a few seconds later.
shot quiet0; xdotool key s; sleep 0.8; shot quiet1; sleep 3.5; shot quiet2
d1=$(differ quiet0 quiet1); d2=$(differ quiet0 quiet2)
grep -q "notice: saved screenshot newtons-cradle-" "$work/app.log" && [ "$d1" != "0" ] && [ "$d2" = "0" ] \
  && ok "S while paused shows a notice, then it goes ($d1 pixels)" || bad "S while paused shows a notice, then it goes ($d1, $d2)"
# A preset from the panel's list (at this size the list opens at 240,57 and
# "realistic" is its second entry), then Ctrl+Z back.
xdotool mousemove --window "$wid" 240 57 click 1; sleep 1
xdotool mousemove --window "$wid" 220 96 click 1; sleep 1.5
grep -q "notice: preset loaded: realistic" "$work/app.log" && ok "a preset loads from the panel" \
  || bad "a preset loads from the panel"
xdotool mousemove --window "$wid" 100 200; xdotool key ctrl+z; sleep 1
grep -q "notice: undone" "$work/app.log" && ok "Ctrl+Z undoes the preset" || bad "Ctrl+Z undoes the preset"
# A click on the balls field starts typing there; Escape then leaves the field,
# not the app.
xdotool mousemove --window "$wid" 316 79 click 1; sleep 0.7; xdotool key Escape; sleep 1
kill -0 "$pid" 2>/dev/null && ok "Escape in a panel field leaves the field, not the app" \
  || bad "Escape in a panel field leaves the field, not the app"
xdotool key Tab; sleep 1

xdotool key space
for i in $(seq 1 45); do xdotool windowsize "$wid" $((300 + (i * 37) % 700)) $((200 + (i * 53) % 500)); done
sleep 2
if kill -0 "$pid" 2>/dev/null; then ok "survives 45 rapid resizes"; else bad "survives 45 rapid resizes"; fi
shot resized1; sleep 1.0; shot resized2
d=$(differ resized1 resized2)
[ "$d" != "0" ] && ok "still draws after resizing" || bad "still draws after resizing"

sed -i 's/balls: 5,/balls: 7,/' "$work/cradle.ron"
sleep 2
grep -q "reloaded" "$work/app.log" && ok "reloads a saved config" || bad "reloads a saved config"
sed -i 's/balls: 7,/balls: 0,/' "$work/cradle.ron"
sleep 2
grep -q "config not reloaded.*balls" "$work/app.log" && kill -0 "$pid" 2>/dev/null \
  && ok "keeps the scene on a bad edit" || bad "keeps the scene on a bad edit"

xdotool windowfocus "$wid" 2>/dev/null; xdotool key s; sleep 1
shotfile=$(ls "$work"/newtons-cradle-*.png 2>/dev/null | head -n 1)
[ -n "$shotfile" ] && [ "$(identify -format %w "$shotfile")" = "480" ] && grep -q "saved screenshot" "$work/app.log" \
  && ok "S saves a screenshot at the framebuffer size" || bad "S saves a screenshot"
xdotool key s s s; sleep 1.5
[ "$(ls "$work"/newtons-cradle-*.png 2>/dev/null | wc -l)" -ge 4 ] \
  && ok "three quick S presses give three more files" || bad "three quick S presses give three more files"

xdotool key Escape
wait_exit
[ "$code" = "0" ] && ok "Escape exits with 0" || bad "Escape exits with 0 (got '${code:-still running}')"
grep -q "panicked" "$work/app.log" && bad "no panic in the log" || ok "no panic in the log"

# Destroyed by another client (XDestroyWindow): exits cleanly, no panic.
"$bin" --config "$(dirname "$bin")/../../assets/cradle.ron" --width 160 --height 80 > "$work/destroy.log" 2>&1 &
pid=$!
wid=$(find_window)
sleep 1; xdotool key --window "$wid" space; sleep 0.5
[ -n "$wid" ] && python3 "$(dirname "$0")/destroy_window.py" "$wid"
wait_exit
[ "$code" = "0" ] && ! grep -q panicked "$work/destroy.log" \
  && ok "destroyed from outside: exits 0" || { bad "destroyed from outside: exits 0 (got '${code:-still running}')"; cat "$work/destroy.log"; }

# Heavy settings still answer Escape at once: the realistic cradle of 200
# balls swinging (its physics slower than the frames: slow motion), and 4K at
# 64 uniform samples (capped to a frame's worth of work).
assets="$(dirname "$bin")/../../assets"
for args in "--config $assets/presets/realistic.ron --balls 200" "--width 3840 --height 2160 --samples 64 --aa uniform"; do
  # shellcheck disable=SC2086
  "$bin" $args > "$work/heavy.log" 2>&1 &
  pid=$!
  wid=$(find_window)
  xdotool windowfocus "$wid" 2>/dev/null; sleep 1; xdotool key space; sleep 3; xdotool key Escape
  wait_exit
  [ "$code" = "0" ] && ok "heavy settings answer Escape ($args)" \
    || { bad "heavy settings answer Escape ($args; got '${code:-still running}')"; kill -9 "$pid" 2>/dev/null; }
done

# No usable adapter (Metal does not exist here): a plain message and exit 1.
WGPU_BACKEND=metal timeout 20 "$bin" --width 64 --height 32 > "$work/noadapter.log" 2>&1
code=$?
[ "$code" = "1" ] && grep -q "No usable graphics adapter" "$work/noadapter.log" && ! grep -q panicked "$work/noadapter.log" \
  && ok "no adapter: message and exit 1" || { bad "no adapter: message and exit 1 (got $code)"; cat "$work/noadapter.log"; }

# shellcheck source=sound.sh
. "$(dirname "$0")/sound.sh"
# shellcheck source=graphs.sh
. "$(dirname "$0")/graphs.sh"
# shellcheck source=replay.sh
. "$(dirname "$0")/replay.sh"

[ "$fail" -eq 0 ] || { echo "--- app log"; cat "$work/app.log"; }
echo "window: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
