#!/usr/bin/env python3
"""Runs scripts/gate_count's structural netlist check on the hand-made netlists of rtl/sv/tests/netlists
(ctest gate_count_netlist_check):

  check_netlist_check.py GATE_COUNT NETLIST_DIR

one_driver.v must pass (exit 0); undriven.v (the net _0_ has a load and no driver) and two_drivers.v
(u_x.q[1] is driven by a flip-flop and an inverter) must fail with exit status 1 and one line on
stderr naming the net and the fault."""
import os
import subprocess
import sys

CASES = [
    ("one_driver.v", 0, None),
    ("undriven.v", 1, "block undriven.v (osu035): net _0_ has no driver; loads: 1 (u_x.q[1]$DFFPOSX1.D)"),
    ("two_drivers.v", 1, "block two_drivers.v (osu035): net u_x.q[1] has 2 drivers (u_x.q[1]$DFFPOSX1.Q, _3_.Y); "
                         "loads: 1 (_2_.A)"),
]


def main():
    if len(sys.argv) != 3:
        print("usage: check_netlist_check.py GATE_COUNT NETLIST_DIR", file=sys.stderr)
        return 2
    gate_count, folder = sys.argv[1:]
    failed = 0
    for name, want_rc, want_msg in CASES:
        proc = subprocess.run([gate_count, "--tech", "osu035", "--check-netlist", os.path.join(folder, name)],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=False)
        lines = proc.stderr.strip().splitlines()
        ok = proc.returncode == want_rc
        if want_msg is not None:
            ok = ok and lines == [f"gate_count: error: {want_msg}"]
        else:
            ok = ok and not lines
        if not ok:
            failed += 1
            print(f"{name}: exit {proc.returncode} (expected {want_rc}), stderr {proc.stderr.strip()!r}"
                  f" (expected {want_msg!r})", file=sys.stderr)
    print(f"{len(CASES) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
