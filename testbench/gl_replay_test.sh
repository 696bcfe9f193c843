#!/usr/bin/env bash
# The GL replay end to end (docs/gl-replay.md): testbench/gl_replay_program.cpp, a tiny GLX program
# that makes every call the replay executes, is traced with apitrace under Xvfb; then
#   - `tfu sim --gl-trace` runs its frame through the cycle model and the golden model: every
#     request equal ("all N equal"), and the frame composed from the unit's outputs;
#   - `tfu render --gl-trace` writes the golden model's frame, whose pixels must be the ones the
#     program derived by hand (its checks file: "x y r g b name" per line), as must the sim's frame
#     (S3TC uploads included: compressed by the replay as a driver does);
#   - the program's variant with fog and glLineWidth is refused with exit 2 and both names in one line,
#     its variant with a sub-image of an S3TC level off the 4 x 4 block grid with exit 2 and the call;
#   - a truncated trace, a frame out of range and a file that is no trace are refused with one line.
# Skipped (77) without apitrace, xvfb-run or Debian's python3 with PIL.
#
#   testbench/gl_replay_test.sh BUILD/bin/tfu BUILD/bin/tfu_gl_replay_program [WORK]
set -euo pipefail
tfu=$(realpath "$1")
program=$(realpath "$2")
work=${3:-$(mktemp -d /tmp/tfu-gl-replay.XXXXXX)}
rm -rf "$work" && mkdir -p "$work"
work=$(realpath "$work")
fail() {
  echo "gl_replay_test: FAIL: $*"
  exit 1
}
for tool in apitrace xvfb-run Xvfb xauth; do
  command -v "$tool" >/dev/null || { echo "gl_replay_test: skipped: $tool not installed"; exit 77; }
done
/usr/bin/python3 -c 'import PIL' 2>/dev/null || { echo "gl_replay_test: skipped: /usr/bin/python3 without PIL"; exit 77; }
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe

# Traces the program (NAME [unsupported]) to $work/NAME.trace, its checks to $work/NAME.checks.
trace() {
  local name=$1
  shift
  timeout 60 xvfb-run -a -s "-screen 0 320x240x24" apitrace trace --api gl -o "$work/$name.trace" "$program" "$work/$name.checks" "$@" \
    >"$work/$name.trace.log" 2>&1 || fail "tracing the program ($name): $(tail -n 3 "$work/$name.trace.log")"
}

# Exit 2 with one error line ("tfu: error: ...", last on stderr) of at most 300 characters matching REGEX.
refused() {
  local regex=$1
  shift
  local rc=0 line
  "$tfu" "$@" >"$work/r.out" 2>"$work/r.err" || rc=$?
  [[ $rc == 2 ]] || fail "tfu $*: exit $rc, want 2 ($(head -c 300 "$work/r.err"))"
  [[ $(grep -c '^tfu: ' "$work/r.err") == 1 ]] || fail "tfu $*: not one error line: $(cat "$work/r.err")"
  line=$(tail -n 1 "$work/r.err")
  ((${#line} <= 300)) || fail "tfu $*: the message is longer than 300 characters"
  grep -Eq -- "$regex" <<<"$line" || fail "tfu $*: the message does not match '$regex': $line"
}

trace ok
[[ -s $work/ok.checks ]] || fail "the program wrote no checks"

# Both models, every request.
"$tfu" sim --gl-trace "$work/ok.trace" --frame 0 --out "$work/sim.png" --force >"$work/sim.out" 2>&1 ||
  fail "tfu sim --gl-trace: $(tail -n 5 "$work/sim.out")"
grep -Eq 'golden compare: all [1-9][0-9]* equal' "$work/sim.out" || fail "tfu sim --gl-trace: no 'all N equal': $(cat "$work/sim.out")"
grep -q 'per stage' "$work/sim.out" || fail "tfu sim --gl-trace: no per-stage statistics"
grep -q 'per texture' "$work/sim.out" || fail "tfu sim --gl-trace: no per-texture statistics"
"$tfu" render --gl-trace "$work/ok.trace" --frame 0 --out "$work/render.png" --force >"$work/render.out" 2>&1 ||
  fail "tfu render --gl-trace: $(tail -n 5 "$work/render.out")"

# The hand-derived pixels, in the golden render and in the frame composed from the unit's outputs.
/usr/bin/python3 - "$work/ok.checks" "$work/render.png" "$work/sim.png" <<'PY' || fail "pixel checks"
import sys
from PIL import Image
checks = [l.split() for l in open(sys.argv[1]) if l.strip()]
bad = 0
for path in sys.argv[2:]:
    im = Image.open(path).convert("RGB")
    assert im.size == (64, 64), f"{path}: size {im.size}, want 64x64"
    for x, y, r, g, b, name in checks:
        got = im.getpixel((int(x), int(y)))
        if got != (int(r), int(g), int(b)):
            print(f"{path}: {name} at ({x}, {y}): got {got}, want ({r}, {g}, {b})")
            bad += 1
print(f"{len(checks)} checks x {len(sys.argv) - 2} images, {bad} wrong")
sys.exit(1 if bad else 0)
PY

# Unsupported calls and states: refused by name, in one line.
trace bad unsupported
refused 'unsupported GL calls or states: .*glEnable\(GL_FOG\) \(call [0-9]+\).*glLineWidth \(call [0-9]+\)' render --gl-trace "$work/bad.trace" --out "$work/bad.png"
[[ ! -e $work/bad.png ]] || fail "a refused replay wrote its image"

# A sub-image of an S3TC level off the 4 x 4 block grid: one line naming the call, exit 2.
trace bad-s3tc bad-s3tc
refused 'call [0-9]+ glTexSubImage2D: the rectangle 4x4 at \(2, 0\) of level 0 \(8x8, GL_COMPRESSED_RGBA_S3TC_DXT1_EXT\) is not made of whole 4x4 blocks' \
  render --gl-trace "$work/bad-s3tc.trace" --out "$work/bad-s3tc.png"
[[ ! -e $work/bad-s3tc.png ]] || fail "a refused replay wrote its image"

# Bad input: a truncated trace, a frame out of range, a file that is no trace.
head -c 20000 "$work/ok.trace" >"$work/truncated.trace"
refused 'truncated\.trace' render --gl-trace "$work/truncated.trace" --out "$work/t.png"
refused 'frame 1 out of range: the trace has 1 frames' render --gl-trace "$work/ok.trace" --frame 1 --out "$work/t.png"
echo "not a trace" >"$work/text.trace"
refused 'text\.trace' sim --gl-trace "$work/text.trace"
refused '--frame needs --gl-trace' render --frame 3
echo "gl_replay_test: OK ($(grep -o 'all [0-9]* equal' "$work/sim.out"))"
