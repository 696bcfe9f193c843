#!/usr/bin/env bash
# The real engine's frames (docs/capture.md): scripts/capture-openarena captures aggressor:0 at
# 160x120, 4 frames, no bots, with one texture cvar changed (r_picmip 0); the test checks capture.json
# against what was asked and what the engine reported, the trace's frame count (apitrace dump), the
# screenshot's size, the engine's eye against the project's spawn rule (gtest Capture.* with
# TFU_CAPTURE_JSON), and Mesa's replays of the screenshot frame (scripts/mesa-frame, tfu compare):
# llvmpipe (the driver the engine ran on) identical to the screenshot, softpipe above 44 dB and
# closer to it than the frame before. Bad input: unknown map, spawn index, size, an existing --out
# without --force: one line, exit 2, nothing written. A missing tool fails the test with one line.
#
#   testbench/capture_openarena_test.sh BUILD/bin/tfu BUILD/bin/tfu_tests [WORK]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
tfu=$(realpath "$1")
tests=$(realpath "$2")
work=${3:-$(mktemp -d /tmp/tfu-capture.XXXXXX)}
capture=$here/scripts/capture-openarena
mesa=$here/scripts/mesa-frame
py=/usr/bin/python3
# Softpipe against the engine's llvmpipe frame: 47.4 dB measured (aggressor:0, 160x120); the frame
# before it 38.5-39.4 dB (the weapon moves). 44 dB lies between with ~3.5 dB on either side.
min_psnr=44

fail() { echo "capture_openarena_test: FAIL: $*"; exit 1; }
for tool in /usr/games/openarena:openarena Xvfb:xvfb apitrace:apitrace glretrace:apitrace \
            /usr/lib/x86_64-linux-gnu/apitrace/wrappers/glxtrace.so:apitrace-tracers $py:python3; do
  path=${tool%%:*} pkg=${tool##*:}
  if [[ $path == /* ]]; then [[ -e $path ]]; else command -v "$path" >/dev/null; fi ||
    fail "missing $path (Debian package $pkg; scripts/bootstrap --test installs it)"
done
$py -c 'import PIL, numpy' 2>/dev/null || fail "missing PIL or numpy for $py (Debian python3-pil, python3-numpy)"

rm -rf "$work" && mkdir -p "$work"
t0=$(date +%s.%N)

# ---- bad input: one line <= 300 characters on stderr, exit 2, nothing written ----
bad() {  # bad EXPECTED-REGEX ARGS...
  local want=$1; shift
  set +e; "$capture" "$@" >"$work/bad.out" 2>"$work/bad.err"; local rc=$?; set -e
  [[ $rc == 2 ]] || fail "capture-openarena $*: exit $rc, expected 2"
  [[ ! -s $work/bad.out ]] || fail "capture-openarena $*: wrote to stdout"
  [[ $(wc -l <"$work/bad.err") == 1 ]] || fail "capture-openarena $*: $(wc -l <"$work/bad.err") lines on stderr"
  (( $(wc -c <"$work/bad.err") <= 301 )) || fail "capture-openarena $*: the error line is longer than 300 characters"
  grep -Eq -- "$want" "$work/bad.err" || fail "capture-openarena $*: '$(cat "$work/bad.err")' does not match '$want'"
}
bad "unknown map 'no_such_level'" no_such_level --frames 4 --size 160x120 --out "$work/bad1"
bad "spawn 9 of oa:aggressor: expected 0\.\.8" aggressor:9 --frames 4 --size 160x120 --out "$work/bad2"
bad "spawn .*-1|expected MAP" aggressor:-1 --frames 4 --size 160x120 --out "$work/bad2"
bad "--size '160x0'" aggressor --frames 4 --size 160x0 --out "$work/bad3"
bad "--size 'big'" aggressor --frames 4 --size big --out "$work/bad3"
bad "--frames 1: expected 2" aggressor --frames 1 --size 160x120 --out "$work/bad4"
bad "--cvar 'r_picmip'" aggressor --frames 4 --size 160x120 --cvar 'r_picmip' --out "$work/bad4"
bad "--cvar 'x=1;quit'" aggressor --frames 4 --size 160x120 --cvar 'x=1;quit' --out "$work/bad4"
mkdir "$work/existing" && echo keep >"$work/existing/mine.txt"
bad "--out '.*existing' exists \(give --force" aggressor --frames 4 --size 160x120 --out "$work/existing"
[[ $(cat "$work/existing/mine.txt") == keep ]] || fail "an existing --out was touched without --force"
for d in bad1 bad2 bad3 bad4; do [[ ! -e $work/$d ]] || fail "a refused run created $d"; done
[[ -z $(find "$work" -maxdepth 1 -name '.capture-openarena-*') ]] || fail "a refused run left a temporary directory"

# ---- one real frame ----
cap=$work/cap
t1=$(date +%s.%N)
"$capture" aggressor:0 --frames 4 --size 160x120 --cvar r_picmip=0 --out "$cap" >"$work/capture.out" 2>"$work/capture.err" ||
  fail "capture-openarena aggressor:0 failed: $(tail -1 "$work/capture.err")"
t2=$(date +%s.%N)
for f in capture.json frames.trace engine.trace screenshot.png engine.log; do
  [[ -s $cap/$f ]] || fail "capture: $f missing"
done
[[ -z $(find "$work" -maxdepth 1 -name '.capture-openarena-*') ]] || fail "the capture left a temporary directory"

# capture.json against what was asked and what the engine said; the frames by apitrace dump.
$py - "$cap" <<'PY' || exit 1
import json, re, subprocess, sys
from PIL import Image
cap = sys.argv[1]
j = json.load(open(f"{cap}/capture.json"))
def check(cond, what):
    if not cond:
        print(f"capture_openarena_test: FAIL: capture.json: {what}")
        sys.exit(1)
check(j["map"] == "aggressor" and j["spawn"]["index"] == 0, f"map/spawn {j['map']}:{j['spawn']['index']}")
check(j["spawn"]["class"] == "info_player_deathmatch", "spawn class")
check(j["size"] == [160, 120] and j["frames"] == 4 and j["bots"] == 0, "size, frames, bots")
check(j["cvars_given"] == {"r_picmip": "0"}, "cvars_given")
tc = j["texture_cvars"]
for k in ["r_textureMode", "r_picmip", "r_ext_compressed_textures", "r_ext_texture_filter_anisotropic",
          "r_detailtextures", "r_dynamiclight", "r_roundImagesDown"]:
    check(k in tc and tc[k] != "", f"texture cvar {k} not recorded")
check(tc["r_picmip"] == "0", f"r_picmip as run is {tc['r_picmip']}, asked 0")
rr = j["renderer_report"]  # the renderer's own start-up report agrees with the queried cvars
check(rr.get("picmip") == "0", f"the renderer reported picmip {rr.get('picmip')}")
check(rr.get("texturemode") == tc["r_textureMode"], "texture mode: renderer report vs cvar")
check(rr.get("compressed_textures") == ("enabled" if tc["r_ext_compressed_textures"] != "0" else "disabled"),
      "compressed textures: renderer report vs cvar")
check(j["run_cvars"]["cl_renderer"] == "opengl1", "renderer")
check(re.match(r"ioq3 1\.36", j["engine"]["version"]) is not None, f"engine version {j['engine']['version']}")
check(j["apitrace_version"].startswith("11.1"), "apitrace version")
check(all(j["packages"][p] for p in ["openarena", "ioquake3", "xvfb", "apitrace", "libgl1-mesa-dri"]), "package versions")
check("aggressor:0" in j["command_line"] and "--cvar r_picmip=0" in j["command_line"], "command line")
check(j["trace"]["screenshot_frame"] == 3 and j["trace"]["setup_frame"] == 0, "frame numbers")
# apitrace's own count of the frames (SwapBuffers calls) of each trace
for name, want in [("frames.trace", 4), ("engine.trace", j["engine_trace"]["frames"])]:
    out = subprocess.run(["apitrace", "dump", "--color=never", f"{cap}/{name}"], capture_output=True, text=True).stdout
    n = len(re.findall(r"^\d+ glXSwapBuffers\(", out, re.M))
    check(n == want, f"{name}: apitrace dump counts {n} frames, expected {want}")
    if name == "engine.trace":  # the screenshot's glReadPixels follows the SwapBuffers of its frame
        calls = [(int(m.group(1)), m.group(2)) for m in re.finditer(r"^(\d+) (glXSwapBuffers|glReadPixels)\(", out, re.M)]
        read = max(c for c, f in calls if f == "glReadPixels")
        check(sum(1 for c, f in calls if f == "glXSwapBuffers" and c < read) - 1 == j["engine_trace"]["screenshot_frame"],
              "engine.trace: screenshot frame")
im = Image.open(f"{cap}/screenshot.png")
check(im.size == (160, 120) and im.mode == "RGB", f"screenshot {im.size} {im.mode}")
PY

# The eye the engine used against the project's spawn rule.
TFU_CAPTURE_JSON=$cap/capture.json "$tests" --gtest_filter='Capture.EngineEyeMatchesTheSpawnRule' --gtest_brief=1 >"$work/gtest.out" 2>&1 ||
  fail "the engine's eye differs from the spawn rule: $(grep -m1 -E 'Failure|rule|Expected' "$work/gtest.out")"
grep -q "1 test.*PASSED\|PASSED.*1 test" "$work/gtest.out" || fail "Capture.* did not run: $(tail -1 "$work/gtest.out")"
grep -q "SKIPPED" "$work/gtest.out" && fail "Capture.* skipped: $(grep -m1 -A1 SKIPPED "$work/gtest.out" | tail -1)"

# Mesa's frames against the engine's screenshot.
psnr() { "$tfu" compare "$1" "$2" | sed -n 's/^psnr_db: //p'; }
t3=$(date +%s.%N)
"$mesa" "$cap/frames.trace" --frame 3 --driver llvmpipe --out "$work/llvmpipe3.png" >/dev/null
"$mesa" "$cap/frames.trace" --frame 2,3 --out "$work/softpipe{frame}.png" >/dev/null
t4=$(date +%s.%N)
same=$(psnr "$cap/screenshot.png" "$work/llvmpipe3.png")
[[ $same == inf ]] || fail "llvmpipe's replay of frame 3 is not the engine's screenshot (PSNR $same dB)"
p3=$(psnr "$cap/screenshot.png" "$work/softpipe3.png")
p2=$(psnr "$cap/screenshot.png" "$work/softpipe2.png")
$py -c "import sys; sys.exit(0 if float('$p3') >= $min_psnr else 1)" ||
  fail "softpipe frame 3 vs the screenshot: PSNR $p3 dB < $min_psnr dB"
$py -c "import sys; sys.exit(0 if float('$p3') > float('$p2') + 3 else 1)" ||
  fail "softpipe frame 2 ($p2 dB) is as close to the screenshot as frame 3 ($p3 dB): frame numbering"
mesa_bad() {  # mesa_bad EXPECTED-REGEX ARGS...: one line, exit 2, --out not written
  local want=$1; shift
  set +e; "$mesa" "$@" >/dev/null 2>"$work/bad.err"; local rc=$?; set -e
  [[ $rc == 2 && $(wc -l <"$work/bad.err") == 1 ]] || fail "mesa-frame $*: exit $rc, $(wc -l <"$work/bad.err") lines"
  grep -Eq -- "$want" "$work/bad.err" || fail "mesa-frame $*: '$(cat "$work/bad.err")' does not match '$want'"
}
mesa_bad "--frame 4: .* holds frames 0\.\.3" "$cap/frames.trace" --frame 4 --out "$work/x.png"
mesa_bad "trace '.*nothing.trace': no such file" "$work/nothing.trace" --frame 0 --out "$work/x.png"
mesa_bad "several frames need \{frame\}" "$cap/frames.trace" --frame 1,2 --out "$work/x.png"
mesa_bad "--out '.*softpipe2.png' exists \(give --force" "$cap/frames.trace" --frame 0 --out "$work/softpipe2.png"
[[ ! -e $work/x.png ]] || fail "a refused mesa-frame wrote its --out"
t5=$(date +%s.%N)
times=$($py -c "print(f'capture {$t2-$t1:.1f} s, 2 Mesa replays {$t4-$t3:.1f} s, total {$t5-$t0:.1f} s')")
echo "capture_openarena_test: aggressor:0 160x120: 4 frames; llvmpipe replay identical; softpipe $p3 dB (frame before: $p2 dB); $times"
