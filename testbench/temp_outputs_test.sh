#!/usr/bin/env bash
# Temporary paths (docs/inputs-outputs.md, TFU-P item 2): a directory with a symbolic link planted
# at the old predictable temporary names ($TMPDIR/tfu_aniso_compare_PID for `tfu aniso-compare`,
# $TMPDIR/tfu-sweep-bench-PID for `tfu sweep --bench`) is left untouched, the file the link points
# to is not written, and nothing of the run is left in $TMPDIR.
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

echo "temp_outputs_test: planted temporary names untouched"
