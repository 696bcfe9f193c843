#!/usr/bin/env bash
# Temporary paths and failed runs (docs/inputs-outputs.md, "Temporary paths" and "Failed runs"):
#   - a directory with a symbolic link planted at the old predictable temporary names
#     ($TMPDIR/tfu_aniso_compare_PID for `tfu aniso-compare`, $TMPDIR/tfu-sweep-bench-PID for
#     `tfu sweep --bench`, P.png.tmp.png for `tfu plot --out P.png`) is left untouched, the file
#     the link points to is not written, and nothing of the run is left in $TMPDIR;
#   - `tfu sweep --plot` with a plot step that fails writes none of results.csv, columns.json,
#     summary.md and the plots (a second run keeps the first run's files as they were);
#   - `tfu plot --out` refuses a directory, a named pipe and a device (also with --force), with one
#     line, leaving them as they were and no temporary behind.
# The PID of a planted name is known in advance: a subshell plants it under its own $BASHPID and
# then execs tfu, which keeps that PID.
#
#   testbench/temp_outputs_test.sh BUILD/bin/tfu [WORK]
set -euo pipefail
tfu=$(realpath "$1")
work=${2:-$(mktemp -d /tmp/tfu-temp-outputs.XXXXXX)}
rm -rf "$work" && mkdir -p "$work"
work=$(realpath "$work")
fail() {
  echo "temp_outputs_test: FAIL: $*"
  exit 1
}
export TMPDIR=$work/tmp
mkdir -p "$TMPDIR"
echo victim >"$work/victim"

# Exit 2 with one error line ("tfu: error: ...", last on stderr; a sweep's progress lines may come
# before it) of at most 300 characters that matches REGEX.
refused() {
  local regex=$1
  shift
  local rc=0 line
  "$tfu" "$@" >"$work/r.out" 2>"$work/r.err" || rc=$?
  [[ $rc == 2 ]] || fail "tfu $*: exit $rc, want 2 ($(head -c 300 "$work/r.err"))"
  [[ $(grep -c '^tfu: ' "$work/r.err") == 1 ]] || fail "tfu $*: not one error line: $(cat "$work/r.err")"
  line=$(tail -n 1 "$work/r.err")
  [[ $line == "tfu: error: "* ]] || fail "tfu $*: the error line is not the last: $(cat "$work/r.err")"
  ((${#line} <= 300)) || fail "tfu $*: the message is longer than 300 characters"
  grep -Eq -- "$regex" <<<"$line" || fail "tfu $*: the message does not match '$regex': $line"
}
# The planted directory $1 still holds exactly its link to the victim, which still reads "victim".
untouched() {
  [[ -d $1 && -L $1/$2 && $(readlink "$1/$2") == "$work/victim" ]] ||
    fail "$3: the planted $1/$2 was changed or removed"
  [[ $(ls -A "$1") == "$2" ]] || fail "$3: files were added to the planted $1: $(ls -A "$1")"
  [[ $(cat "$work/victim") == victim ]] || fail "$3: wrote through the link planted at $1/$2"
  [[ $(ls -A "$TMPDIR") == "$(basename "$1")" ]] || fail "$3: left in \$TMPDIR: $(ls -A "$TMPDIR")"
}

# 1. tfu aniso-compare: texture0.tif in the planted directory links to the victim.
(
  d=$TMPDIR/tfu_aniso_compare_$BASHPID
  mkdir "$d" && ln -s "$work/victim" "$d/texture0.tif"
  exec "$tfu" aniso-compare --scene grazing --width 16 --height 12 >"$work/aniso.txt" 2>&1
) || fail "aniso-compare: exit $? ($(tail -n 3 "$work/aniso.txt"))"
grep -q 'OIIO trilinear' "$work/aniso.txt" || fail "aniso-compare printed no comparison"
planted=$(ls -d "$TMPDIR"/tfu_aniso_compare_*)
untouched "$planted" texture0.tif "aniso-compare"
rm -rf "$planted"

# 2. tfu sweep --bench: the planted directory holds a link (and the bench points' files would go there).
cat >"$work/spec.json" <<'EOF'
{"scenes": ["ground_plane"], "filters": ["bilinear"], "width": 16, "height": 12,
 "grid": {"cache.capacity_bytes": [2048, 8192]}}
EOF
(
  d=$TMPDIR/tfu-sweep-bench-$BASHPID
  mkdir "$d" && ln -s "$work/victim" "$d/points"
  exec "$tfu" sweep "$work/spec.json" --bench --workers 1 >"$work/bench.txt" 2>&1
) || fail "sweep --bench: exit $? ($(tail -n 3 "$work/bench.txt"))"
grep -q 'tfu sweep --bench: 2 points' "$work/bench.txt" || fail "sweep --bench printed no report"
planted=$(ls -d "$TMPDIR"/tfu-sweep-bench-*)
untouched "$planted" points "sweep --bench"
rm -rf "$planted"

# 3. tfu plot --out P.png: P.png.tmp.png is a link to the victim.
mkdir -p "$work/csv"
printf 'x,y\n1,2\n2,3\n4,5\n' >"$work/csv/results.csv"
ln -s "$work/victim" "$work/P.png.tmp.png"
"$tfu" plot "$work/csv" --x x --y y --out "$work/P.png" >/dev/null || fail "plot --out P.png: exit $?"
[[ $(head -c 4 "$work/P.png" | tail -c 3) == PNG ]] || fail "plot --out P.png wrote no PNG"
[[ -L $work/P.png.tmp.png && $(cat "$work/victim") == victim ]] || fail "plot wrote through the link at P.png.tmp.png"
# scripts/plot on its own (without tfu's --write-to) writes its temporary by mkstemp as well.
plot_script=$(cd "$(dirname "$0")/.." && pwd)/scripts/plot
ln -s "$work/victim" "$work/Q.png.tmp.png"
/usr/bin/python3 "$plot_script" --csv "$work/csv/results.csv" --x x --y y --out "$work/Q.png" >/dev/null ||
  fail "scripts/plot --out Q.png: exit $?"
[[ $(head -c 4 "$work/Q.png" | tail -c 3) == PNG ]] || fail "scripts/plot --out Q.png wrote no PNG"
[[ -L $work/Q.png.tmp.png && $(cat "$work/victim") == victim ]] || fail "scripts/plot wrote through Q.png.tmp.png"

# 4. tfu plot --out on what is not a regular file: refused (also with --force), left as it was.
mkdir "$work/D.png"
refused "--out '.*D\.png' exists and is a directory" plot "$work/csv" --x x --y y --out "$work/D.png" --force
[[ -d $work/D.png && -z $(ls -A "$work/D.png") ]] || fail "plot --out DIR.png changed the directory"
mkfifo "$work/fifo.png"
for force in "" --force; do
  refused "--out '.*fifo\.png' exists and is a named pipe" plot "$work/csv" --x x --y y --out "$work/fifo.png" $force
  [[ -p $work/fifo.png ]] || fail "plot --out FIFO $force replaced the named pipe"
done
ln -s /dev/null "$work/null.png"
refused "--out '.*null\.png' exists and is a character device" \
  plot "$work/csv" --x x --y y --out "$work/null.png" --force
[[ -L $work/null.png && -c /dev/null ]] || fail "plot --out DEVICE --force replaced the device"
leftovers=$(find "$work" -name '*.tmp.png' -o -name '.tfu-*.tmp' -o -name '.plot-*' |
  grep -v "$work/[PQ].png.tmp.png" || true)
[[ -z $leftovers ]] || fail "temporaries left behind: $leftovers"

# 5. tfu sweep --plot with a failing plot step: nothing of the summary is written.
cat >"$work/failing_plot" <<'EOF'
#!/usr/bin/python3
import sys
print("plot: error: the plot step failed (test)", file=sys.stderr)
sys.exit(2)
EOF
chmod +x "$work/failing_plot"
TFU_PLOT_SCRIPT=$work/failing_plot refused "plot: the plot step failed \(test\)" \
  sweep "$work/spec.json" --out "$work/sw" --quiet --plot
for f in results.csv columns.json summary.md plot_area.png; do
  [[ ! -e $work/sw/$f ]] || fail "sweep --plot with a failing plot step left $f"
done
# A plot script that is missing is found out before anything runs or is written.
TFU_PLOT_SCRIPT=$work/no_such_plot refused "plot script '.*no_such_plot' not found" \
  sweep "$work/spec.json" --out "$work/sw2" --quiet --plot
[[ ! -e $work/sw2 ]] || fail "sweep --plot with a missing plot script created --out"
# A sweep that completed, then --collect --plot with the failing step: the first run's files stay.
"$tfu" sweep "$work/spec.json" --out "$work/sw" --quiet >/dev/null 2>&1 || fail "sweep: exit $?"
echo "earlier" >>"$work/sw/results.csv"  # the files as they were, marked: a new run would not write this line
cp "$work/sw/results.csv" "$work/results.csv.before"
cp "$work/sw/summary.md" "$work/summary.md.before"
TFU_PLOT_SCRIPT=$work/failing_plot refused "plot: the plot step failed" sweep --collect "$work/sw" --plot
for f in results.csv summary.md; do
  cmp -s "$work/sw/$f" "$work/$f.before" || fail "sweep --collect --plot with a failing plot step replaced $f"
done
leftovers=$(find "$work/sw" -name '.tfu-*.tmp' -o -name 'plot_*')
[[ -z $leftovers ]] || fail "sweep --plot left: $leftovers"
echo "temp_outputs_test: planted temporary names untouched; failed runs and special files leave nothing"
