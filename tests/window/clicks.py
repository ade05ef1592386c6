"""Reads a raw recording of the sink (48 kHz, 16-bit stereo) and judges it.

clicks.py rhythm FILE   clicks at the default cradle's half period (exit 0), or not (1)
clicks.py silence FILE  nothing but silence (exit 0), or not (1)
"""
import math
import struct
import sys

RATE = 48000


def samples(path):
    raw = open(path, "rb").read()
    n = len(raw) // 4
    s = struct.unpack("<%dh" % (2 * n), raw[: 4 * n])
    return [max(abs(s[2 * i]), abs(s[2 * i + 1])) for i in range(n)]


def onsets(mono, threshold=1000, quiet=0.1):
    """Sample indices where a click starts: above the threshold after at
    least `quiet` seconds below it."""
    found, last = [], -(10**9)
    for i, v in enumerate(mono):
        if v > threshold:
            if i - last > quiet * RATE:
                found.append(i)
            last = i
    return found


def half_period():
    """The default cradle's half period (s): 16 cm strings, 2 cm steel balls
    lifted 30 degrees, a physical pendulum, T/2 = 2 K(sin 15 deg) / w0."""
    length, radius, g, angle = 0.16, 0.02, 9.81, math.radians(30)
    w0 = math.sqrt(g * length / (length**2 + 0.4 * radius**2))
    a, b = 1.0, math.sqrt(1 - math.sin(angle / 2) ** 2)
    for _ in range(40):
        a, b = (a + b) / 2, math.sqrt(a * b)
    k = math.pi / (2 * a)
    return 2 * k / w0


def main():
    what, path = sys.argv[1], sys.argv[2]
    mono = samples(path)
    if what == "silence":
        peak = max(mono, default=0)
        print(f"peak {peak} over {len(mono) / RATE:.1f} s")
        return 0 if peak <= 1 and len(mono) > RATE else 1
    starts = onsets(mono)
    gaps = sorted((b - a) / RATE for a, b in zip(starts, starts[1:]))
    want = half_period()
    if len(gaps) < 3:
        print(f"{len(starts)} clicks in {len(mono) / RATE:.1f} s")
        return 1
    median = gaps[len(gaps) // 2]
    print(f"{len(starts)} clicks, {median:.4f} s apart (half period {want:.4f} s)")
    # 2%: the clicks are placed by the audio server's clock, a few ms apart
    # from frame to frame; the rhythm itself is the physics'.
    return 0 if abs(median / want - 1) < 0.02 else 1


if __name__ == "__main__":
    sys.exit(main())
