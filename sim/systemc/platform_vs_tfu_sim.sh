#!/bin/bash
# The SystemC example platform against the tfu binary: on a trace of testbench/data and on a
# built-in scene's trace written by `tfu render --trace-out`, the cycle count the platform reads
# from the unit's CYCLES registers equals the one `tfu sim --requests` prints (and the platform's
# --check compares its pixels with the cycle model and the golden model).
# usage: platform_vs_tfu_sim.sh TFU EXAMPLE DATA_DIR WORK_DIR
set -euo pipefail
tfu=$1 example=$2 data=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
"$tfu" render --scene lightmapped --width 96 --height 64 --out "$work/lightmapped.png" --trace-out "$work/lightmapped.txt" >/dev/null
cycles_of() { sed -n 's/^  cycles \([0-9][0-9]*\) .*/\1/p'; }
for trace in "$data/two_textures.txt" "$work/lightmapped.txt"; do
  want=$("$tfu" sim --requests "$trace" | cycles_of)
  got=$("$example" --requests "$trace" --check | cycles_of)
  if [[ -z $want || $want != "$got" ]]; then
    echo "FAIL $trace: tfu sim cycles '$want', SystemC platform cycles '$got'"
    exit 1
  fi
  echo "ok $trace: $got cycles in both"
done
