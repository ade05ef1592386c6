#!/usr/bin/env bash
# The real-window test: runs tests/window/inner.sh on a virtual X display with
# software Vulkan (../shared/tools/with-display.sh installs what is missing).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
tool="$root/../shared/tools/with-display.sh"
[ -x "$tool" ] || { echo "window test: $tool not found" >&2; exit 1; }
if ! command -v python3 >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends python3
fi
cargo build --release --quiet --manifest-path "$root/Cargo.toml"
exec "$tool" "$here/inner.sh" "$root/target/release/newtons-cradle"
