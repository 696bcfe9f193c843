#!/usr/bin/env bash
# The plot step's inputs (TFU-S E5, E7; docs/inputs-outputs.md "Input files"): `tfu plot DIR` and
# scripts/plot read results.csv and columns.json (and scripts/filter_gates its --gates) through the
# same checks as every other input (scripts/tfu_inputs.py): a named pipe is refused without waiting
# for a writer, /dev/zero behind a link without reading it; a malformed CSV (a short row, bytes that
# are not UTF-8) is one line naming the file and the line, and a failure no check foresaw is one
# line with the exception, never a Python traceback. Each case: exit 2, one line of at most 300
# characters, no PNG and no temporary.
#
#   testbench/plot_inputs_test.sh BUILD/bin/tfu [WORK]
set -euo pipefail
tfu=$(realpath "$1")
root=$(cd "$(dirname "$0")/.." && pwd)
work=${2:-$(mktemp -d /tmp/tfu-plot-inputs.XXXXXX)}
rm -rf "$work" && mkdir -p "$work"
work=$(realpath "$work")
fail() {
  echo "plot_inputs_test: FAIL: $*"
  exit 1
}
# refused REGEX PROGRAM ARGS...: exit 2 within 60 s, one stderr line matching REGEX, no PNG written.
refused() {
  local regex=$1
  shift
  local rc=0
  rm -f "$work/out.png"
  timeout 60 "$@" >"$work/r.out" 2>"$work/r.err" || rc=$?
  [[ $rc == 2 ]] || fail "$*: exit $rc, want 2 ($(head -c 300 "$work/r.err"))"
  [[ $(wc -l <"$work/r.err") == 1 ]] || fail "$*: not one line on stderr: $(head -c 600 "$work/r.err")"
  (($(wc -c <"$work/r.err") <= 301)) || fail "$*: the message is longer than 300 characters"
  grep -Eq -- "$regex" "$work/r.err" || fail "$*: the message does not match '$regex': $(cat "$work/r.err")"
  [[ ! -e $work/out.png ]] || fail "$*: wrote the PNG"
}
sweep_dir() {  # a sweep directory with this results.csv text
  mkdir -p "$work/$1"
  printf "$2" >"$work/$1/results.csv"
}
sweep_dir ok 'x,y,error\n1,2,\n2,3,\n'
"$tfu" plot "$work/ok" --x x --y y --out "$work/ok.png" >/dev/null || fail "a good results.csv: exit $?"
[[ -s $work/ok.png ]] || fail "a good results.csv drew nothing"

mkdir -p "$work/fifo" && mkfifo "$work/fifo/results.csv"
refused "plot: --csv '.*fifo/results\.csv': is a named pipe \(FIFO\), not a regular file" \
  "$tfu" plot "$work/fifo" --x x --y y --out "$work/out.png"
mkdir -p "$work/zero" && ln -s /dev/zero "$work/zero/results.csv"
refused "plot: --csv '.*zero/results\.csv': is a character device, not a regular file" \
  "$tfu" plot "$work/zero" --x x --y y --out "$work/out.png"
sweep_dir columns_fifo 'x,y,error\n1,2,\n' && mkfifo "$work/columns_fifo/columns.json"
refused "plot: --columns '.*columns_fifo/columns\.json': is a named pipe" \
  "$tfu" plot "$work/columns_fifo" --x x --y y --out "$work/out.png"
sweep_dir columns_bad 'x,y,error\n1,2,\n' && echo '[{"name": ["x"]}]' >"$work/columns_bad/columns.json"
refused "plot: --columns '.*columns_bad/columns\.json': malformed" "$tfu" plot "$work/columns_bad" --x x --y y --out "$work/out.png"
# A short row was a TypeError traceback, and tfu printed its first line, "Traceback (most recent call last):".
sweep_dir short 'x,y,error\n1,2,\n2\n'
refused "plot: --csv '.*short/results\.csv':3: 1 fields, the header has 3" "$tfu" plot "$work/short" --x x --y y --out "$work/out.png"
sweep_dir latin1 'x,y,error\n1,\xe92,\n'
refused "plot: --csv '.*latin1/results\.csv': not UTF-8 text \(byte 12\)" "$tfu" plot "$work/latin1" --x x --y y --out "$work/out.png"
# The script run directly: the same checks, and argparse's usage errors as one line.
refused "^plot: error: --csv '/dev/zero': is a character device" /usr/bin/python3 "$root/scripts/plot" --csv /dev/zero --x x --y y --out "$work/out.png"
refused "^plot: error: the following arguments are required: --x, --y, --out" /usr/bin/python3 "$root/scripts/plot" --csv "$work/ok/results.csv"
# scripts/filter_gates reads its --gates through the same checks
refused "^filter_gates: error: --gates '/dev/zero': is a character device" /usr/bin/python3 "$root/scripts/filter_gates" --gates /dev/zero --out "$work/fg.json"
# A plot step that fails with a traceback all the same: tfu names its exception, not "Traceback".
cat >"$work/traceback_plot" <<'PY'
#!/usr/bin/python3
import sys
sys.argv.index("--no-such-argument")
PY
chmod +x "$work/traceback_plot"
TFU_PLOT_SCRIPT=$work/traceback_plot refused "tfu: error: plot: ValueError: '--no-such-argument' is not in list" \
  "$tfu" plot "$work/ok" --x x --y y --out "$work/out.png"
leftovers=$(find "$work" -name '.tfu-*.tmp' -o -name '.plot-*')
[[ -z $leftovers ]] || fail "temporaries left behind: $leftovers"
echo "plot_inputs_test: FIFOs, devices, malformed CSV and columns refused with one line; no traceback"
