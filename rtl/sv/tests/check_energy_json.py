#!/usr/bin/env python3
"""Checks the JSON of scripts/energy --block on one block (ctest energy_osu035_smoke):

  check_energy_json.py ZEROS.json RANDOM.json RANDOM_HALF_CLOCK.json

ZEROS / RANDOM: the same block, node and clock on the all-zeros and the random stream; the third the
random stream at half the clock. Asserts: every power positive where it must be (leakage always,
total and dynamic power on the random stream), the all-zeros stream's dynamic power below the random
stream's, the leakage the same on both streams and at both clocks (the OSU cells' leakage is
state-independent), pJ per pixel equal to power / pixel rate recomputed from the JSON's own fields,
and at half the clock the dynamic power halved while the dynamic energy per pixel stays the same
(one pixel per clock, zero-delay toggles: the toggles per pixel do not depend on the clock).
"""
import json
import math
import sys


def fail(msg):
    print(f"check_energy_json: {msg}", file=sys.stderr)
    sys.exit(1)


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def dynamic(r):
    t = r["power_w"]["total"]
    return t["internal"] + t["switching"]


def main():
    if len(sys.argv) != 4:
        fail("usage: check_energy_json.py ZEROS.json RANDOM.json RANDOM_HALF_CLOCK.json")
    zeros, rnd, half = (load(p) for p in sys.argv[1:])
    for name, r in (("zeros", zeros), ("random", rnd), ("random at half clock", half)):
        for key in ("block", "tech", "clock_mhz", "pixels", "power_w", "uniform_power_w", "pj_per_pixel",
                    "pixels_per_second", "mean_toggles_per_net"):
            if key not in r:
                fail(f"{name}: missing field {key}")
        t = r["power_w"]["total"]
        if not t["leakage"] > 0:
            fail(f"{name}: leakage {t['leakage']} not positive")
        if abs(t["total"] - (t["internal"] + t["switching"] + t["leakage"])) > 1e-9 * max(t["total"], 1e-30):
            fail(f"{name}: total {t['total']} is not internal + switching + leakage")
        if r["pixels_per_second"] != r["clock_mhz"] * 1e6:
            fail(f"{name}: pixel rate {r['pixels_per_second']} is not one pixel per clock ({r['clock_mhz']} MHz)")
        want = t["total"] / r["pixels_per_second"] * 1e12
        if not math.isclose(r["pj_per_pixel"], want, rel_tol=1e-9):
            fail(f"{name}: pj_per_pixel {r['pj_per_pixel']} but power / pixel rate = {want}")
    if zeros["block"] != rnd["block"] or zeros["tech"] != rnd["tech"] or zeros["clock_mhz"] != rnd["clock_mhz"]:
        fail("zeros and random must be the same block, node and clock")
    if not (rnd["power_w"]["total"]["total"] > 0 and dynamic(rnd) > 0):
        fail(f"random stream: power {rnd['power_w']['total']} not positive")
    if not dynamic(zeros) < dynamic(rnd):
        fail(f"dynamic power on the all-zeros stream {dynamic(zeros)} W is not below the random stream's {dynamic(rnd)} W")
    if not (0.05 < rnd["mean_toggles_per_net"] < 1.0) or zeros["mean_toggles_per_net"] != 0:
        fail(f"mean toggles per net: zeros {zeros['mean_toggles_per_net']} (expected 0), random "
             f"{rnd['mean_toggles_per_net']} (expected between 0.05 and 1)")
    lz, lr, lh = (r["power_w"]["total"]["leakage"] for r in (zeros, rnd, half))
    if not (math.isclose(lz, lr, rel_tol=1e-9) and math.isclose(lr, lh, rel_tol=1e-9)):
        fail(f"leakage depends on the stream or the clock: {lz} {lr} {lh} W")
    if not math.isclose(half["clock_mhz"] * 2, rnd["clock_mhz"], rel_tol=1e-9):
        fail(f"the third file must be at half the clock ({half['clock_mhz']} vs {rnd['clock_mhz']} MHz)")
    if not math.isclose(dynamic(half) * 2, dynamic(rnd), rel_tol=1e-4):
        fail(f"dynamic power at half the clock {dynamic(half)} W is not half of {dynamic(rnd)} W")
    print(f"check_energy_json: {rnd['block']} {rnd['tech']}: random {rnd['pj_per_pixel']:.3f} pJ/pixel "
          f"(mean toggles {rnd['mean_toggles_per_net']:.3f}), zeros {zeros['pj_per_pixel']:.6f} pJ/pixel, "
          f"leakage {lr * 1e9:.2f} nW: ok")


if __name__ == "__main__":
    main()
