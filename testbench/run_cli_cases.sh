#!/usr/bin/env bash
# Runs every case of a cases file against the tfu binary; fails on the first broken expectation.
# Case file format, one case per line ('#' starts a comment line):
#   EXIT | REGEX | ARGS...
# EXIT is the expected exit code; REGEX an extended regular expression that the combined
# stdout+stderr must match ('-' for none); ARGS are passed to tfu as words ({WORK} expands to a
# scratch directory, {DATA} to testbench/data, {LONG:N} to N letters 'a', for over-long names;
# a word {EMPTY} is passed as an empty argument). A
# case with EXIT 2 must also print exactly one line on stderr, and no case may print a stderr line
# longer than 300 characters.
set -u
tfu=$1 cases=$2 work=$3
data=$(cd "$(dirname "$cases")" && pwd)/data
rm -rf "$work" && mkdir -p "$work"
n=0 failed=0
while IFS= read -r line; do
  [[ -z "${line// }" || "$line" == \#* ]] && continue
  IFS='|' read -r want regex args <<<"$line"
  want=${want// /}; regex=$(sed -e 's/^ *//' -e 's/ *$//' <<<"$regex")
  args=${args//\{WORK\}/$work}
  args=${args//\{DATA\}/$data}
  while [[ "$args" =~ \{LONG:([0-9]+)\} ]]; do
    long=$(printf 'a%.0s' $(seq "${BASH_REMATCH[1]}"))
    args=${args/"${BASH_REMATCH[0]}"/$long}
  done
  n=$((n + 1))
  read -r -a argv <<<"$args"
  for i in "${!argv[@]}"; do [[ "${argv[$i]}" == "{EMPTY}" ]] && argv[$i]=""; done
  timeout 120 "$tfu" "${argv[@]}" >"$work/out.txt" 2>"$work/err.txt"
  got=$?
  ok=1
  [[ "$got" == "$want" ]] || ok=0
  if [[ "$regex" != "-" ]] && ! cat "$work/out.txt" "$work/err.txt" | grep -Eq -- "$regex"; then ok=0; fi
  if [[ "$want" == 2 ]] && [[ $(wc -l <"$work/err.txt") -ne 1 ]]; then ok=0; fi
  if [[ $(awk '{ if (length($0) > m) m = length($0) } END { print m + 0 }' "$work/err.txt") -gt 300 ]]; then ok=0; fi
  if [[ $ok == 0 ]]; then
    failed=$((failed + 1))
    echo "FAIL: tfu $args (exit $got, want $want, regex '$regex')"
    sed 's/^/  stdout: /' "$work/out.txt" | head -5 | cut -c1-400
    sed 's/^/  stderr: /' "$work/err.txt" | head -5 | cut -c1-400
  fi
done <"$cases"
# Outputs are written to temporaries and renamed when complete: no run, failed or not, leaves one.
if leftovers=$(find "$work" -name '.tfu-*.tmp' | head -5) && [[ -n "$leftovers" ]]; then
  failed=$((failed + 1))
  echo "FAIL: temporary output files left behind: $leftovers"
fi
echo "cli cases: $((n - failed)) passed, $failed failed"
[[ $failed == 0 ]]
