#!/usr/bin/env bash
# The batch script of `tfu sweep --slurm` against hostile names, without Slurm (docs/inputs-outputs.md,
# "Temporary files and generated scripts"). The tfu binary is copied into a directory whose name holds
# every character the shell treats specially (spaces, quotes, $(...), backticks, ;, #, glob characters,
# a backslash), and the sweep goes to --out directories of the same kind (with '%' patterns of
# sbatch's --output, %j and %%, and no backslash, which sbatch's patterns cannot carry), with an
# --sbatch-arg of the first kind:
#   - the --slurm-dry-run script and the script that --slurm hands to a fake sbatch (which records
#     its arguments) are run under bash, with the binary replaced by a stub that records its
#     arguments: the stub must receive exactly `sweep --run-task T --tasks N --workers C --out DIR`,
#     the fake sbatch exactly `--parsable ARG SCRIPT`, the #SBATCH --output value must read back as
#     DIR/slurm/task-%a.log with DIR's '%' written %% (sbatch then reads it as DIR), and none of
#     the injected commands may have run;
#   - names with a newline or a carriage return (--out, --sbatch-arg), and an --out with a
#     backslash, are refused with one line naming the option (exit 2), before anything is written
#     or submitted;
#   - a submission that fails (sbatch exits 1) removes the --out it created, and leaves an existing
#     sweep directory as it was.
#
#   testbench/slurm_script_test.sh BUILD/bin/tfu [WORK]
set -euo pipefail
tfu=$(realpath "$1")
work=${2:-$(mktemp -d /tmp/tfu-slurm-script.XXXXXX)}
rm -rf "$work" && mkdir -p "$work"
work=$(realpath "$work")
fail() {
  echo "slurm_script_test: FAIL: $*"
  exit 1
}

# Injected commands touch MARK* files in the current directory, which is $work/cwd while anything runs.
hostile=" a b'c\"d\$(touch MARK1)\`touch MARK2\`;touch MARK3 &touch MARK4|x #*?[ab]{1,2}~!\\e"
# An --out directory: the same without the backslash, with sbatch's own pattern characters.
hostile_dir=" a b'c\"d\$(touch MARK1)\`touch MARK2\`;touch MARK3 &touch MARK4|x #*?[ab]{1,2}~! %j %% 100%"
mkdir -p "$work/cwd" "$work/fakebin"
cwd=$work/cwd
bindir="$work/bin$hostile"
mkdir -p "$bindir"
cp "$tfu" "$bindir/tfu"
cat >"$work/spec.json" <<'EOF'
{"scenes": ["ground_plane"], "filters": ["bilinear"], "width": 16, "height": 12,
 "grid": {"cache.capacity_bytes": [2048, 8192]}}
EOF
# The fake sbatch: records its arguments (NUL-separated) and a copy of the script; prints a job id.
cat >"$work/fakebin/sbatch" <<EOF
#!/bin/bash
printf '%s\\0' "\$@" >'$work/sbatch.argv'
cp -- "\${@: -1}" '$work/submitted.sbatch'
echo 4242
EOF
chmod +x "$work/fakebin/sbatch"
export PATH="$work/fakebin:$PATH"

no_marks() {
  local left
  left=$(ls -A "$cwd")
  [[ -z $left ]] || fail "$1: an injected command ran (left in the working directory: $left)"
}

# 1. The dry run: the script is the output without its last line (the sbatch command, a comment).
out_dry="$work/dry$hostile_dir"
(cd "$cwd" && "$bindir/tfu" sweep "$work/spec.json" --out "$out_dry" --slurm-dry-run --tasks 2 \
  --sbatch-arg="--comment=$hostile") >"$work/dry.txt"
no_marks "the dry run"
sed '$d' "$work/dry.txt" >"$work/dry.sbatch"
tail -n 1 "$work/dry.txt" | grep -q "^# 2 points in 2 array tasks; would run: 'sbatch' '--parsable'" ||
  fail "the dry run's last line is not the sbatch command: $(tail -n 1 "$work/dry.txt")"
[[ ! -e $out_dry ]] || fail "the dry run created --out"

# 2. --slurm with the fake sbatch: the script written to DIR/slurm/sweep.sbatch and submitted.
out_sub="$work/sub$hostile_dir"
(cd "$cwd" && "$bindir/tfu" sweep "$work/spec.json" --out "$out_sub" --slurm --tasks 2 \
  --sbatch-arg="--comment=$hostile") >"$work/sub.txt"
no_marks "--slurm"
grep -q 'submitted as Slurm job 4242' "$work/sub.txt" ||
  fail "--slurm did not report the fake job: $(cat "$work/sub.txt")"
printf '%s\0' --parsable "--comment=$hostile" "$out_sub/slurm/sweep.sbatch" >"$work/sbatch.want"
cmp -s "$work/sbatch.argv" "$work/sbatch.want" || fail "sbatch got other arguments: $(tr '\0' '|' <"$work/sbatch.argv")"
cmp -s "$work/submitted.sbatch" "$out_sub/slurm/sweep.sbatch" || fail "sbatch was not handed DIR/slurm/sweep.sbatch"

# The binary replaced by a stub that records its arguments.
rm "$bindir/tfu"
cat >"$bindir/tfu" <<EOF
#!/bin/bash
printf '%s\\0' "\$@" >'$work/stub.argv'
EOF
chmod +x "$bindir/tfu"

# Runs a script as one array task would, and checks what the stub got and what the #SBATCH
# --output value reads back as (bash's reading of the quotes; sbatch reads the same quotes).
run_script() {
  local script=$1 dir=$2 line value
  rm -f "$work/stub.argv"
  (cd "$cwd" && SLURM_ARRAY_TASK_ID=1 SLURM_CPUS_PER_TASK=3 bash "$script") || fail "$script: exit $?"
  no_marks "$script"
  [[ -e $work/stub.argv ]] || fail "$script did not run the tfu binary"
  printf '%s\0' sweep --run-task 1 --tasks 2 --workers 3 --out "$dir" >"$work/stub.want"
  cmp -s "$work/stub.argv" "$work/stub.want" ||
    fail "$script ran tfu with other arguments: $(tr '\0' '|' <"$work/stub.argv")"
  line=$(grep '^#SBATCH --output=' "$script") || fail "$script has no #SBATCH --output line"
  value=$(cd "$cwd" && eval "printf '%s' ${line#\#SBATCH --output=}")
  no_marks "the #SBATCH --output value of $script"
  [[ $value == "${dir//%/%%}/slurm/task-%a.log" ]] || fail "$script: #SBATCH --output reads back as '$value'"
}
run_script "$work/dry.sbatch" "$out_dry"
run_script "$out_sub/slurm/sweep.sbatch" "$out_sub"

# 3. Newlines and carriage returns cannot be quoted into a line of the script: refused with one line.
refused() {
  local what=$1
  shift
  local rc=0
  rm -f "$work/sbatch.argv"
  (cd "$cwd" && "$tfu" "$@") >"$work/r.out" 2>"$work/r.err" || rc=$?
  [[ $rc == 2 ]] || fail "$what: exit $rc, want 2 ($(head -c 300 "$work/r.out" "$work/r.err"))"
  [[ $(wc -l <"$work/r.err") == 1 ]] || fail "$what: not one line on stderr: $(cat "$work/r.err")"
  (($(wc -c <"$work/r.err") <= 301)) || fail "$what: the message is longer than 300 characters"
  grep -q -- "${what%% *}" "$work/r.err" || fail "$what: the message does not name the option: $(cat "$work/r.err")"
  [[ ! -s $work/r.out ]] || fail "$what: printed a script: $(head -c 300 "$work/r.out")"
  [[ ! -e $work/sbatch.argv ]] || fail "$what: sbatch was run"
  no_marks "$what"
}
for mode in --slurm-dry-run --slurm; do
  for c in $'\n' $'\r'; do
    bad="$work/nl${c}touch MARK5 #"
    refused "--out ($mode)" sweep "$work/spec.json" --out "$bad" "$mode"
    [[ ! -e $bad ]] || fail "--out with a control character ($mode) was created"
    refused "--sbatch-arg ($mode)" sweep "$work/spec.json" --out "$work/ok" "$mode" \
      "--sbatch-arg=--comment=x${c}touch MARK6"
    [[ ! -e $work/ok ]] || fail "--sbatch-arg with a control character ($mode): --out was created"
  done
  bad="$work/back\\slash"
  refused "--out ($mode)" sweep "$work/spec.json" --out "$bad" "$mode"
  [[ ! -e $bad ]] || fail "--out with a backslash ($mode) was created"
done

# 4. A submission that fails leaves what it found (TFU-S E8): a new --out is removed; in a sweep
#    directory that existed (a local run's), its files stay and the batch script is not left.
mkdir -p "$work/failbin"
printf '#!/bin/bash\necho "sbatch: error: invalid partition specified: test" >&2\nexit 1\n' >"$work/failbin/sbatch"
chmod +x "$work/failbin/sbatch"
rc=0
(cd "$cwd" && PATH="$work/failbin:$PATH" "$tfu" sweep "$work/spec.json" --out "$work/failed" --slurm) \
  >"$work/r.out" 2>"$work/r.err" || rc=$?
[[ $rc == 2 && $(wc -l <"$work/r.err") == 1 ]] || fail "a failing sbatch: exit $rc ($(cat "$work/r.err"))"
grep -q "sbatch failed (status 1): sbatch: error: invalid partition" "$work/r.err" || fail "a failing sbatch: $(cat "$work/r.err")"
[[ ! -e $work/failed ]] || fail "a failing sbatch left the new --out: $(find "$work/failed")"
"$tfu" sweep "$work/spec.json" --out "$work/local" --quiet >/dev/null 2>&1 || fail "the local sweep: exit $?"
before=$(cd "$work/local" && find . -type f | sort | xargs md5sum)
rc=0
(cd "$cwd" && PATH="$work/failbin:$PATH" "$tfu" sweep "$work/spec.json" --out "$work/local" --slurm) \
  >"$work/r.out" 2>"$work/r.err" || rc=$?
[[ $rc == 2 ]] || fail "a failing sbatch on a sweep directory: exit $rc"
after=$(cd "$work/local" && find . -type f | sort | xargs md5sum)
[[ $before == "$after" && ! -e $work/local/slurm ]] || fail "a failing sbatch changed the sweep directory: $(find "$work/local")"
no_marks "a failing sbatch"
echo "slurm_script_test: hostile names ran nothing but the sweep; newline, carriage return and an --out backslash refused; a failed submission leaves nothing"
