#!/usr/bin/env python3
"""Checks two gates_<tech>.json files written by scripts/gate_count --tech osu035|osu018 for the same
blocks at a looser and a tighter clock target (the gate_count_osu035_smoke test):

- every named block is present with the fields of docs/silicon.md: positive area, NAND2X1
  equivalents equal to area / NAND2X1 area, cells, leakage and register-to-register fmax; a
  flip-flop count; a critical path with a start, an end and at least one cell;
- fmax agrees with the slack: for a block measured between wrapper registers every path is
  register-to-register, so fmax = 1 / (period - worst slack), and the worst slack is negative
  exactly when fmax is below the clock target;
- the clock target does not change what the block is: the area at the tighter target is not smaller
  than at the looser one (a tighter target makes ABC map for delay and upsize the critical paths);
- with --faster PIPELINED:UNPIPELINED (both among the blocks): the pipelined variant of a top reaches
  a higher register-to-register clock than the unpipelined one at the tighter target.

usage: check_silicon_json.py LOOSE.json TIGHT.json [--faster PIPELINED:UNPIPELINED]... BLOCK...
"""
import json
import sys


def num(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def check_row(r, errors):
    name = r.get("block", "?")
    for key in ("area_um2", "nand2_eq", "nand2_area_um2", "cells", "leakage_nw", "fmax_reg2reg_mhz", "clock_mhz"):
        if not num(r.get(key)) or not r[key] > 0:
            errors.append(f"{name}: {key} = {r.get(key)!r} is not a positive number")
    if not isinstance(r.get("flip_flops"), int) or isinstance(r.get("flip_flops"), bool) or r["flip_flops"] < 0:
        errors.append(f"{name}: flip_flops = {r.get('flip_flops')!r} is not a count")
    if not num(r.get("worst_slack_ns")):
        errors.append(f"{name}: worst_slack_ns = {r.get('worst_slack_ns')!r} is not a number")
    cp = r.get("critical_path")
    if not isinstance(cp, dict) or not cp.get("start") or not cp.get("end") or not isinstance(cp.get("cells"), int) \
            or cp["cells"] < 1:
        errors.append(f"{name}: critical_path = {cp!r} lacks a start, an end or cells")
    if errors:
        return
    if abs(r["nand2_eq"] - r["area_um2"] / r["nand2_area_um2"]) > 0.1:
        errors.append(f"{name}: nand2_eq {r['nand2_eq']} is not area / NAND2X1 area")
    if r.get("wrapped"):
        period = 1000.0 / r["clock_mhz"]
        expect = 1000.0 / (period - r["worst_slack_ns"])
        if abs(r["fmax_reg2reg_mhz"] - expect) > 0.005 * expect + 0.1:
            errors.append(f"{name}: fmax {r['fmax_reg2reg_mhz']} MHz does not match the slack ({expect:.1f} MHz)")
        if (r["worst_slack_ns"] < 0) != (r["fmax_reg2reg_mhz"] < r["clock_mhz"]):
            errors.append(f"{name}: slack {r['worst_slack_ns']} ns and fmax {r['fmax_reg2reg_mhz']} MHz disagree "
                          f"at {r['clock_mhz']} MHz")


def main():
    args = sys.argv[3:]
    faster = []
    while len(args) >= 2 and args[0] == "--faster":
        pair = args[1].split(":")
        if len(pair) != 2 or not all(pair):
            print(f"check_silicon_json: --faster {args[1]}: expected PIPELINED:UNPIPELINED", file=sys.stderr)
            return 2
        faster.append(pair)
        args = args[2:]
    if len(sys.argv) < 4 or not args:
        print("usage: check_silicon_json.py LOOSE.json TIGHT.json [--faster PIPELINED:UNPIPELINED]... BLOCK...",
              file=sys.stderr)
        return 2
    runs = []
    for path in sys.argv[1:3]:
        with open(path, encoding="utf-8") as f:
            runs.append({r.get("block"): r for r in json.load(f) if isinstance(r, dict)})
    errors = []
    for block in args:
        rows = [run.get(block) for run in runs]
        if None in rows:
            errors.append(f"block {block} missing")
            continue
        before = len(errors)
        for r in rows:
            check_row(r, errors)
        if len(errors) > before:
            continue
        loose, tight = rows
        if not tight["clock_mhz"] > loose["clock_mhz"]:
            errors.append(f"{block}: the second file's clock {tight['clock_mhz']} is not the tighter one")
        elif tight["area_um2"] < loose["area_um2"]:
            errors.append(f"{block}: {tight['area_um2']} um^2 at {tight['clock_mhz']} MHz is smaller than "
                          f"{loose['area_um2']} um^2 at {loose['clock_mhz']} MHz")
        if len(errors) > before:
            continue
        print(f"check_silicon_json: {block}: {loose['area_um2']:.0f} um^2 at {loose['clock_mhz']:g} MHz, "
              f"{tight['area_um2']:.0f} um^2 at {tight['clock_mhz']:g} MHz, fmax {tight['fmax_reg2reg_mhz']} MHz")
    for piped, unpiped in faster:
        fast, slow = runs[1].get(piped), runs[1].get(unpiped)
        if fast is None or slow is None:
            errors.append(f"--faster {piped}:{unpiped}: a block is missing")
        elif not num(fast.get("fmax_reg2reg_mhz")) or not num(slow.get("fmax_reg2reg_mhz")):
            errors.append(f"--faster {piped}:{unpiped}: fmax missing")
        elif not fast["fmax_reg2reg_mhz"] > slow["fmax_reg2reg_mhz"]:
            errors.append(f"{piped} reaches {fast['fmax_reg2reg_mhz']} MHz, not more than {unpiped} "
                          f"({slow['fmax_reg2reg_mhz']} MHz)")
        else:
            print(f"check_silicon_json: {piped} {fast['fmax_reg2reg_mhz']} MHz > {unpiped} {slow['fmax_reg2reg_mhz']} MHz")
    for e in errors:
        print(f"check_silicon_json: {e}", file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
