#!/usr/bin/env python3
"""Checks a gates.json written by scripts/gate_count: a list of objects with the required fields,
positive numbers, and every block named on the command line present (the gate_count_smoke test)."""
import json
import sys


def main():
    if len(sys.argv) < 2:
        print("usage: check_gates_json.py GATES.json [BLOCK...]", file=sys.stderr)
        return 2
    with open(sys.argv[1], encoding="utf-8") as f:
        rows = json.load(f)
    errors = []
    if not isinstance(rows, list) or not rows:
        errors.append("expected a non-empty JSON array")
        rows = []
    for r in rows:
        name = r.get("block", "?") if isinstance(r, dict) else "?"
        if not isinstance(r, dict):
            errors.append("an entry is not an object")
            continue
        for key in ("block", "top"):
            if not isinstance(r.get(key), str) or not r[key]:
                errors.append(f"{name}: missing {key}")
        for key in ("ge", "depth", "cells", "cmos_transistors", "cmos_ge"):
            v = r.get(key)
            if not isinstance(v, (int, float)) or isinstance(v, bool) or not v > 0:
                errors.append(f"{name}: {key} = {v!r} is not a positive number")
        ff = r.get("flip_flops")
        if not isinstance(ff, int) or isinstance(ff, bool) or ff < 0:
            errors.append(f"{name}: flip_flops = {ff!r} is not a count")
        if "compare_cells" in r and (not isinstance(r["compare_cells"], int) or r["compare_cells"] <= 0):
            errors.append(f"{name}: compare_cells = {r['compare_cells']!r} is not a positive integer")
        # The two figures come from different mappings of the same netlist; they must agree roughly.
        if isinstance(r.get("ge"), (int, float)) and isinstance(r.get("cmos_ge"), (int, float)) and r["ge"] > 0:
            ratio = r["cmos_ge"] / r["ge"]
            if not 0.5 < ratio < 2.0:
                errors.append(f"{name}: CMOS cross-check {r['cmos_ge']} is far from {r['ge']} GE")
    names = {r.get("block") for r in rows if isinstance(r, dict)}
    for want in sys.argv[2:]:
        if want not in names:
            errors.append(f"block {want} missing")
    for e in errors:
        print(f"check_gates_json: {e}", file=sys.stderr)
    if errors:
        return 1
    print(f"check_gates_json: {len(rows)} blocks OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
