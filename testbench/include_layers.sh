#!/usr/bin/env bash
# The house's layering, checked from the sources: no include arrow runs from a lower room to a
# higher one. Rooms, lowest first:
#   cmodel/       the golden model                    may include cmodel/
#   rtl/kernel/   the simulation kernel               may include rtl/kernel/ and two leaf headers of
#                                                     cmodel/ (no project includes of their own):
#                                                     error_kinds.hpp and json_output.hpp
#   rtl/          the cycle model and the SV tools    may include cmodel/, rtl/
#   sim/          the CLI and the sweeps              may include cmodel/, rtl/, sim/
#   testbench/ and every tests/ folder (rtl/sv/*/tests/): above all, may include anything
# Every project include is written from the source root ("cmodel/x.hpp"), so the room an include
# names is its first path component.
#   include_layers.sh SOURCE_ROOT            checks the tree; each upward include is one line, exit 1
#   include_layers.sh --self-test SCRATCH    plants one upward include per rule in a copy of a tiny
#                                            tree and checks that each is found (the check can fail)
set -uo pipefail

# check ROOT: prints "file:line: ROOM must not include TARGET" for every upward include.
check() {
  local root=$1 bad=0 file line target room
  while IFS=: read -r file line target; do
    room=${file%%/*}
    [[ $file == */tests/* || $room == testbench ]] && continue
    case $file in
      rtl/kernel/*)
        [[ $target == rtl/kernel/* || $target == cmodel/error_kinds.hpp || $target == cmodel/json_output.hpp ]] && continue
        room=rtl/kernel ;;
      cmodel/*) [[ $target == cmodel/* ]] && continue ;;
      rtl/*) [[ $target == cmodel/* || $target == rtl/* ]] && continue ;;
      sim/*) [[ $target == cmodel/* || $target == rtl/* || $target == sim/* ]] && continue ;;
      *) continue ;;
    esac
    echo "$file:$line: $room/ must not include \"$target\" (a higher room; testbench/include_layers.sh)"
    bad=1
  done < <(cd "$root" && grep -rnoE --include='*.cpp' --include='*.hpp' --include='*.h' \
             '^[[:space:]]*#[[:space:]]*include[[:space:]]+"(cmodel|rtl|sim|testbench)/[^"]+"' cmodel rtl sim 2>/dev/null |
           sed -E 's/^([^:]+):([0-9]+):.*"([^"]+)"$/\1:\2:\3/')
  return $bad
}

if [[ ${1:-} == --self-test ]]; then
  scratch=$2
  rm -rf "$scratch" && mkdir -p "$scratch"
  fail=0
  # plant NAME FILE INCLUDE: a tree whose one file has one include; the check must refuse it.
  plant() {
    local dir="$scratch/$1"
    mkdir -p "$dir/cmodel" "$dir/rtl/kernel" "$dir/rtl/sv/tests" "$dir/sim" "$dir/testbench"
    mkdir -p "$dir/$(dirname "$2")"
    printf '#include "%s"\n' "$3" > "$dir/$2"
    if [[ $4 == refused ]] && check "$dir" >/dev/null; then echo "self-test: $2 including $3 was not refused"; fail=1; fi
    if [[ $4 == allowed ]] && ! check "$dir" >/dev/null; then echo "self-test: $2 including $3 was refused"; fail=1; fi
  }
  plant a cmodel/x.hpp rtl/tfu_unit.hpp refused
  plant b cmodel/x.cpp sim/sweep/sweep_spec.hpp refused
  plant c rtl/x.hpp sim/tfu/commands.hpp refused
  plant d rtl/kernel/x.cpp rtl/unit_ports.hpp refused
  plant e rtl/kernel/x.hpp cmodel/error.hpp refused
  plant f sim/x.cpp testbench/iterations.hpp refused
  plant g rtl/x.cpp testbench/iterations.hpp refused
  plant h rtl/x.cpp cmodel/sampler.hpp allowed
  plant i rtl/kernel/x.hpp cmodel/error_kinds.hpp allowed
  plant j rtl/sv/tests/x.cpp testbench/iterations.hpp allowed
  plant k sim/x.cpp rtl/kernel/kernel.hpp allowed
  [[ $fail == 0 ]] && echo "self-test: every planted upward include refused, every allowed one passed"
  exit $fail
fi

check "${1:?usage: include_layers.sh SOURCE_ROOT | --self-test SCRATCH}" && echo "include layers: no upward include"
