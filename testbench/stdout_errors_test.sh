#!/usr/bin/env bash
# Standard output that cannot be written (docs/inputs-outputs.md: "Standard output is checked when
# the program ends"): exit 2 and one line on stderr, "tfu: error: cannot write to standard output",
#   - when stdout is a pipe whose reader has gone (TFU-S E15: tfu was killed by SIGPIPE, exit 141,
#     with nothing said): the pipe's read end is closed before tfu starts, so the first write fails;
#   - when stdout is /dev/full, for commands that print a summary line on stderr after their outputs
#     (TFU-S E14: the summary came first and the error was the second line).
# (That a child tfu runs gets SIGPIPE's default disposition back: gtest Process.*.)
#
#   testbench/stdout_errors_test.sh BUILD/bin/tfu [WORK]
set -euo pipefail
tfu=$(realpath "$1")
work=${2:-$(mktemp -d /tmp/tfu-stdout-errors.XXXXXX)}
rm -rf "$work" && mkdir -p "$work"
work=$(realpath "$work")
fail() {
  echo "stdout_errors_test: FAIL: $*"
  exit 1
}
want_line="tfu: error: cannot write to standard output"
# A pipe with no reader: /usr/bin/python3 makes it, closes the read end, runs tfu with the write end
# as stdout (subprocess gives the child SIGPIPE's default disposition, as a shell does).
closed_pipe() {
  /usr/bin/python3 - "$tfu" "$@" <<'PY'
import os, subprocess, sys
r, w = os.pipe()
os.close(r)
p = subprocess.run(sys.argv[1:], stdout=w, stderr=subprocess.PIPE)
sys.stderr.buffer.write(p.stderr)
print(p.returncode)
PY
}
for args in "rom --samples 512" "rom --kind direction" "descriptors" "formats" "render --scene magnified --width 16 --height 16 --out $work/p.png --force"; do
  # shellcheck disable=SC2086
  rc=$(closed_pipe $args 2>"$work/err.txt")
  [[ $rc == 2 ]] || fail "tfu $args | (closed): exit $rc, want 2 (-13: killed by SIGPIPE)"
  [[ $(cat "$work/err.txt") == "$want_line" ]] || fail "tfu $args | (closed): stderr is not the one line: $(head -c 400 "$work/err.txt")"
done
for args in "render --scene magnified --width 16 --height 16 --out $work/r.png --force" \
  "formats --json $work/f.json --force" "compare $work/p.png $work/r.png --json $work/c.json --force"; do
  rc=0
  # shellcheck disable=SC2086
  "$tfu" $args >/dev/full 2>"$work/err.txt" || rc=$?
  [[ $rc == 2 ]] || fail "tfu $args >/dev/full: exit $rc, want 2"
  [[ $(cat "$work/err.txt") == "$want_line" ]] || fail "tfu $args >/dev/full: stderr is not the one line: $(head -c 400 "$work/err.txt")"
done
echo "stdout_errors_test: a closed pipe and a full disk behind stdout are one error line, exit 2"
