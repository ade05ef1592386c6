# V, sourced by inner.sh (its ok/bad/find_window/wait_exit): after 11 s of
# swinging, V saves the last 10 s as an animated PNG of 300 frames or more,
# with the clicks heard as a WAV of the same name, and a notice says where.
rm -f "$work"/newtons-cradle-*.png "$work"/newtons-cradle-*.wav
"$bin" --width 480 --height 240 > "$work/replay.log" 2>&1 &
pid=$!
wid=$(find_window)
xdotool windowfocus "$wid" 2>/dev/null; sleep 1
xdotool key space; sleep 11
xdotool key v
for _ in $(seq 1 120); do grep -q "notice: saved .* frames" "$work/replay.log" && break; sleep 0.5; done
xdotool key Escape
wait_exit
apng=$(ls "$work"/newtons-cradle-*.png 2>/dev/null | head -n 1)
frames=$([ -n "$apng" ] && python3 -c '
import struct, sys
data = open(sys.argv[1], "rb").read()
at = 8
while at < len(data):
    n, kind = struct.unpack(">I4s", data[at:at + 8])
    if kind == b"acTL":
        print(struct.unpack(">I", data[at + 8:at + 12])[0]); break
    at += 12 + n
' "$apng")
wav="${apng%.png}.wav"
seconds=$([ -f "$wav" ] && python3 -c '
import sys, wave
w = wave.open(sys.argv[1]); print(round(w.getnframes() / w.getframerate(), 1))
' "$wav")
[ "${frames:-0}" -ge 300 ] && grep -q "notice: saved" "$work/replay.log" \
  && ok "V saves the last 10 s ($frames frames, $(basename "$apng"))" \
  || { bad "V saves the last 10 s (frames '${frames}')"; tail -5 "$work/replay.log"; }
[ -n "$seconds" ] && awk "BEGIN { exit !($seconds >= 9.5 && $seconds <= 10.5) }" \
  && ok "with its clicks as a WAV of the same name ($seconds s)" \
  || bad "with its clicks as a WAV of the same name ('$seconds')"
