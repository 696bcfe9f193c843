#!/usr/bin/env python3
"""Checks scripts/gate_count's refusal of parameter values that Yosys 0.23 reads otherwise than
Verilator (an unbased unsized '1, 'x or 'z: one bit, zero-extended; docs/silicon-log.md, 2026-12-06)
(ctest gate_count_yosys_literals):

  check_yosys_literals.py GATE_COUNT CASE_DIR BUILD

param_fill.sv must be refused with one line naming the file and line 10; fills_accepted.sv must pass;
and so must every source of every block of the manifests (the generated ones from BUILD/rtl/sv/gen)."""
import importlib.machinery
import importlib.util
import os
import sys


def main():
    if len(sys.argv) != 4:
        print("usage: check_yosys_literals.py GATE_COUNT CASE_DIR BUILD", file=sys.stderr)
        return 2
    gate_count, folder, build = sys.argv[1:]
    loader = importlib.machinery.SourceFileLoader("gate_count", gate_count)
    spec = importlib.util.spec_from_loader("gate_count", loader)
    gc = importlib.util.module_from_spec(spec)
    loader.exec_module(gc)
    failed = 0
    bad = os.path.join(folder, "param_fill.sv")
    want = (f"{bad}:10: parameter value with '1: Yosys 0.23 reads it as 1 bit, not the declared width; "
            "write a replication such as {16{1'b1}}")
    try:
        gc.check_yosys_literals(bad)
        failed += 1
        print("param_fill.sv: accepted (expected refused)", file=sys.stderr)
    except gc.InputError as e:
        if str(e) != want:
            failed += 1
            print(f"param_fill.sv: {e!s} (expected {want!r})", file=sys.stderr)
    sources = {os.path.join(folder, "fills_accepted.sv"): None}
    for block in gc.load_blocks():
        sources.update((s, build) for s in block.get("sources", []))
    for source, where in sources.items():
        try:  # resolve() checks the file as gate_count does before every synthesis
            if where is None:
                gc.check_yosys_literals(source)
            else:
                gc.resolve(source, where)
        except gc.InputError as e:
            failed += 1
            print(f"refused: {e}", file=sys.stderr)
    print(f"{len(sources)} sources checked, param_fill.sv refused; {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
