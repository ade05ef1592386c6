# The window's sound, sourced by inner.sh (its ok/bad/find_window/wait_exit):
# with a PulseAudio null sink (check.sh starts one; TEST_SINK names it), the
# swinging cradle's clicks recorded from the sink's monitor come at the
# swing's rhythm, heard within 50 ms of their frames and without underruns;
# started with --mute the sink hears silence until M; without an audio server
# the app runs silently and says why in one line.
if [ -z "${TEST_SINK:-}" ]; then
  bad "sound: no audio server was started for the test"
  return
fi
here="$(dirname "$0")"
# Records the sink for $1 seconds into $2 (raw 48 kHz 16-bit stereo).
record() {
  parec --device="$TEST_SINK.monitor" --format=s16le --rate=48000 --channels=2 --raw > "$2" &
  local rec=$!
  sleep "$1"
  kill "$rec" 2>/dev/null; wait "$rec" 2>/dev/null
}
# Starts the app with the flags given, its log in $log, and lets it swing.
swing() {
  "$bin" "$@" > "$log" 2>&1 &
  pid=$!
  wid=$(find_window)
  xdotool windowfocus "$wid" 2>/dev/null; sleep 1
  xdotool key space
}

log="$work/sound.log"
swing --width 320 --height 200
record 6 "$work/swing.raw"
xdotool key Escape
wait_exit
verdict=$(python3 "$here/clicks.py" rhythm "$work/swing.raw")
[ $? -eq 0 ] && ok "clicks at the swing's rhythm ($verdict)" || bad "clicks at the swing's rhythm ($verdict)"
line=$(grep -o "sound: [0-9]* clicks.*" "$work/sound.log")
late=$(echo "$line" | sed -n 's/.* and at most \([0-9]*\) ms after.*/\1/p')
under=$(echo "$line" | sed -n 's/.*; \([0-9]*\) underruns;.*/\1/p')
[ -n "$late" ] && [ "$late" -le 50 ] && [ "$under" = "0" ] \
  && ok "clicks heard at most 50 ms after their frames, no underrun ($line)" \
  || bad "clicks heard at most 50 ms after their frames, no underrun ('$line')"

log="$work/muted.log"
swing --width 320 --height 200 --mute
record 3 "$work/muted.raw"
xdotool key m
record 3 "$work/unmuted.raw"
xdotool key Escape
wait_exit
verdict=$(python3 "$here/clicks.py" silence "$work/muted.raw")
[ $? -eq 0 ] && ok "--mute: silence while it swings ($verdict)" || bad "--mute: silence while it swings ($verdict)"
verdict=$(python3 "$here/clicks.py" rhythm "$work/unmuted.raw")
[ $? -eq 0 ] && ok "M unmutes: clicks again ($verdict)" || bad "M unmutes: clicks again ($verdict)"

# No audio server: silent, one line saying why, and the window works.
env -u XDG_RUNTIME_DIR -u PULSE_RUNTIME_PATH PULSE_SERVER=unix:/nonexistent/native \
  "$bin" --width 160 --height 80 > "$work/nosound.log" 2>&1 &
pid=$!
wid=$(find_window)
xdotool windowfocus "$wid" 2>/dev/null; sleep 1; xdotool key space; sleep 1; xdotool key Escape
wait_exit
[ "$code" = "0" ] && [ "$(grep -c "sound off: no audio server" "$work/nosound.log")" = "1" ] \
  && ok "no audio server: runs silently, says so once" \
  || { bad "no audio server: runs silently, says so once (exit '${code:-still running}')"; cat "$work/nosound.log"; }
