#!/usr/bin/env bash
# The GL replay on the real game's frame (docs/gl-replay.md, "Against Mesa"): scripts/capture-openarena
# captures aggressor:0 at 160x120 (2 frames: the set-up frame and the screenshot frame, r_picmip 0);
# frame 1 is replayed through both models (`tfu sim --gl-trace`: every request equal, the frame from
# the cycle model's outputs equal to the golden replay's), rendered by Mesa's softpipe
# (scripts/mesa-frame, glretrace), and the two compared with `tfu compare`: at least 40 dB PSNR
# (docs/gl-replay.md "Against Mesa": 46-52 dB measured on aggressor and oa_dm5; the differences are
# rasterization rules, blending rounding and the 8-bit filter arithmetic). Skipped (77) only without the engine (Debian openarena); any other missing tool fails
# with one line naming its package (scripts/bootstrap --test installs them).
#
#   testbench/gl_replay_openarena_test.sh BUILD/bin/tfu [WORK]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
tfu=$(realpath "$1")
work=${2:-$(mktemp -d /tmp/tfu-gl-replay-oa.XXXXXX)}
py=/usr/bin/python3
min_psnr=40

fail() { echo "gl_replay_openarena_test: FAIL: $*"; exit 1; }
[[ -x /usr/games/openarena ]] || { echo "gl_replay_openarena_test: skipped: /usr/games/openarena not installed (Debian openarena)"; exit 77; }
for tool in Xvfb:xvfb apitrace:apitrace glretrace:apitrace \
            /usr/lib/x86_64-linux-gnu/apitrace/wrappers/glxtrace.so:apitrace-tracers $py:python3; do
  path=${tool%%:*} pkg=${tool##*:}
  if [[ $path == /* ]]; then [[ -e $path ]]; else command -v "$path" >/dev/null; fi ||
    fail "missing $path (Debian package $pkg; scripts/bootstrap --test installs it)"
done
$py -c 'import PIL, numpy' 2>/dev/null || fail "missing PIL or numpy for $py (Debian python3-pil, python3-numpy)"
rm -rf "$work" && mkdir -p "$work"
now() { date +%s.%N; }
secs() { $py -c "print(f'{$2 - $1:.1f}')"; }
t0=$(now)

"$here/scripts/capture-openarena" aggressor:0 --frames 2 --size 160x120 --cvar r_picmip=0 --out "$work/cap" \
  >"$work/capture.log" 2>&1 || fail "capture-openarena: $(tail -n 1 "$work/capture.log")"
trace=$work/cap/frames.trace
t1=$(now)

# Both models, every request of the frame. "all N equal" is printed only when every output is equal
# and the frame composed from the cycle model's outputs is the golden replay's frame, pixel for pixel:
# sim.png is the golden model's frame.
"$tfu" sim --gl-trace "$trace" --frame 1 --out "$work/golden.png" --force >"$work/sim.out" 2>&1 ||
  fail "tfu sim --gl-trace: $(tail -n 3 "$work/sim.out")"
grep -Eq 'golden compare: all [1-9][0-9]* equal' "$work/sim.out" || fail "tfu sim --gl-trace: no 'all N equal': $(tail -n 5 "$work/sim.out")"
t2=$(now)

# Mesa's softpipe on the same frame, and the comparison.
"$here/scripts/mesa-frame" "$trace" --frame 1 --out "$work/mesa.png" --force >"$work/mesa.log" 2>&1 ||
  fail "mesa-frame: $(tail -n 1 "$work/mesa.log")"
t3=$(now)
"$tfu" compare "$work/golden.png" "$work/mesa.png" >"$work/compare.out" 2>&1 || fail "tfu compare: $(tail -n 1 "$work/compare.out")"
psnr=$(sed -n 's/^psnr_db: //p' "$work/compare.out")
[[ -n $psnr ]] || fail "tfu compare printed no psnr_db: $(cat "$work/compare.out")"
$py -c "import sys; sys.exit(0 if float('$psnr') >= $min_psnr else 1)" ||
  fail "golden replay vs Mesa softpipe: $psnr dB < $min_psnr dB ($(grep max_abs_diff: "$work/compare.out"))"
echo "gl_replay_openarena_test: OK ($(grep -o 'all [0-9]* equal' "$work/sim.out"); vs softpipe $psnr dB;" \
  "capture $(secs "$t0" "$t1") s, both models $(secs "$t1" "$t2") s, softpipe $(secs "$t2" "$t3") s, total $(secs "$t0" "$(now)") s)"
