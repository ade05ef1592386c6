#!/usr/bin/env bash
# The real-window test: runs tests/window/inner.sh on a virtual X display with
# software Vulkan (with-display.sh beside it installs what is missing),
# and a PulseAudio server with a null sink for its sound checks.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
tool="$here/with-display.sh"
[ -x "$tool" ] || { echo "window test: $tool not found" >&2; exit 1; }
if ! command -v python3 >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends python3
fi
if ! command -v pulseaudio >/dev/null || ! command -v parec >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    pulseaudio pulseaudio-utils
fi
cargo build --release --quiet --manifest-path "$root/Cargo.toml"

# A private audio server: its socket in a runtime folder of its own, one null
# sink (the default) whose monitor the checks record. PULSE_SERVER names it to
# the app and parec (the display's wrapper sets a runtime folder of its own).
audio="$(mktemp -d)"
chmod 700 "$audio"
trap 'XDG_RUNTIME_DIR="$audio" pulseaudio --kill 2>/dev/null; rm -rf "$audio"' EXIT
if XDG_RUNTIME_DIR="$audio" pulseaudio -n --daemonize=yes --exit-idle-time=-1 --disallow-exit \
    --load="module-null-sink sink_name=cradle_test" --load="module-native-protocol-unix" 2>/dev/null; then
  for _ in $(seq 1 50); do [ -S "$audio/pulse/native" ] && break; sleep 0.1; done
  export PULSE_SERVER="unix:$audio/pulse/native" TEST_SINK=cradle_test
else
  echo "window test: could not start pulseaudio; the sound checks will fail" >&2
fi
"$tool" "$here/inner.sh" "$root/target/release/newtons-cradle"
