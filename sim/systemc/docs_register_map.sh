#!/bin/bash
# docs/systemc.md's register tables equal what `tfu_systemc_example --register-map` prints from
# the field tables of sim/systemc/tfu_tlm.cpp (the one definition).
# usage: docs_register_map.sh EXAMPLE DOCS_MD
set -euo pipefail
example=$1 doc=$2
want=$("$example" --register-map)
got=$(sed -n '/^<!-- begin generated: tfu_systemc_example --register-map -->$/,/^<!-- end generated -->$/p' "$doc" | sed '1d;$d')
if [[ "$want" != "$got" ]]; then
  echo "FAIL: $doc's register tables differ from tfu_systemc_example --register-map:"
  diff <(echo "$got") <(echo "$want") | head -20
  exit 1
fi
echo "ok: $doc shows the register map's tables"
