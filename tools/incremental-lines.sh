#!/usr/bin/env bash
# Where an incremental frame's instructions go, line by line of the tracer's
# own source: callgrind counts frames A and B of `bench render --threads 1
# --mode incremental --width 1200 --height 600`, and the difference over B - A
# frames is given to the line of `crates/cradle-trace/src` nearest each
# instruction, code inlined from the standard library, glam or the lane
# builds (`simd/`) going to the tracer's line that called it (`addr2line
# -i`), which callgrind's own per-line view cannot do.
#
#   tools/incremental-lines.sh A B [FUNCTION] [-- BENCH RENDER FLAGS...]
#
# FUNCTION (say `cradle_trace::retrace::moved::Moved::dirty`) counts only
# what runs inside it. Prints the total and the 60 costliest lines (TOP=N for
# more). Needs valgrind and binutils; builds a release binary with line tables
# into target/prof (minutes the first time).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
a="${1:?usage: incremental-lines.sh A B [FUNCTION] [-- FLAGS...]}"
b="${2:?usage: incremental-lines.sh A B [FUNCTION] [-- FLAGS...]}"
shift 2
func=""
if [ $# -gt 0 ] && [ "$1" != "--" ]; then func="$1"; shift; fi
[ "${1:-}" = "--" ] && shift
[ "$b" -gt "$a" ] || { echo "B must be above A" >&2; exit 2; }
for tool in valgrind addr2line python3; do
  command -v "$tool" >/dev/null || { echo "needs $tool" >&2; exit 1; }
done
CARGO_TARGET_DIR="$root/target/prof" CARGO_PROFILE_RELEASE_DEBUG=line-tables-only \
  cargo build --release --quiet --bin newtons-cradle --manifest-path "$root/Cargo.toml"
bin="$root/target/prof/release/newtons-cradle"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
toggle=()
[ -n "$func" ] && toggle=(--toggle-collect="$func")
for n in "$a" "$b"; do
  valgrind --tool=callgrind --dump-instr=yes "${toggle[@]}" --callgrind-out-file="$out/cg.$n" \
    "$bin" bench render --threads 1 --mode incremental --frames "$n" --width 1200 --height 600 "$@" \
    >/dev/null 2>"$out/log.$n"
done
python3 - "$out/cg.$a" "$out/cg.$b" "$((b - a))" "$bin" "${TOP:-60}" <<'EOF'
import collections, re, subprocess, sys

def costs(path):
    """Instructions per address (the `positions: instr line` format)."""
    cost, addr, in_call = collections.Counter(), 0, False
    for raw in open(path):
        if raw.startswith("calls="):
            in_call = True
            continue
        m = re.match(r"^(0x[0-9a-f]+|[+-]\d+|\*)\s+([+-]?\d+|\*)\s+(\d+)", raw)
        if not m:
            continue
        pos = m.group(1)
        if pos.startswith("0x"):
            addr = int(pos, 16)
        elif pos != "*":
            addr += int(pos)
        if in_call:  # a call's inclusive cost: counted where it is spent
            in_call = False
            continue
        cost[addr] += int(m.group(3))
    return cost

first, second, frames, binary, top = sys.argv[1:6]
a, b = costs(first), costs(second)
diff = {k: (b[k] - a[k]) / int(frames) for k in set(a) | set(b) if b[k] != a[k]}
addrs = sorted(diff)
text = subprocess.run(["addr2line", "-a", "-i", "-e", binary],
                      input="\n".join(hex(x) for x in addrs) + "\n",
                      capture_output=True, text=True, check=True).stdout.split("\n")
frames_of, cur = {}, None
for line in text:
    if re.fullmatch(r"0x[0-9a-f]+", line):
        cur = int(line, 16)
        frames_of[cur] = []
    elif cur is not None and line:
        frames_of[cur].append(line)
ours = "/crates/cradle-trace/src/"
lines = collections.Counter()
for addr, c in diff.items():
    # The tracer's lines that hold the instruction, innermost first; the lane
    # builds' one-operation wrappers (simd/) give way to their caller.
    held = [f.split(ours, 1)[1].split(" ")[0] for f in frames_of.get(addr, []) if ours in f]
    mine = [h for h in held if not h.startswith("simd/")] or held
    lines[mine[0] if mine else "elsewhere (the physics, libc)"] += c
print(f"total {sum(lines.values()) / 1e6:.3f}M instructions a frame")
for where, c in lines.most_common(int(top)):
    print(f"{c / 1e6:8.3f}M  {where}")
EOF
