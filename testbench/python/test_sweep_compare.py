# The module's sweeps and image metrics against `tfu sweep` (rows, results.csv) and `tfu compare`.
import math
import os

import pytest
from PIL import Image

import tfu
from conftest import data, read_json


# ---- sweeps ----

def test_sweep_rows_equal_results_csv(cli, tmp_path):
    import csv
    spec = data(os.path.join("sweep", "tiny.json"))
    cli.run("sweep", spec, "--out", tmp_path / "cli", "--quiet")
    rows = tfu.sweep(spec, str(tmp_path / "py"))
    assert rows == tfu.sweep_rows(str(tmp_path / "cli"))
    with open(tmp_path / "cli" / "results.csv") as f:
        table = list(csv.DictReader(f))
    assert len(rows) == len(table) == 8
    for row, want in zip(rows, table):
        assert list(row) == list(want)
        assert row["cache.capacity_bytes"] in (2048, 8192) and row["golden_equal"] is True
        for key, text in want.items():
            value = row[key]
            if value is None:  # a column with no value at this point (e.g. DRAM energy with the ideal memory)
                assert text == "", key
            elif isinstance(value, bool):
                assert text == ("true" if value else "false")
            elif isinstance(value, (int, float)):
                # results.csv writes some columns with fewer digits (energies: 2 decimals): within
                # half a unit of the last digit written
                decimals = len(text.split(".")[1]) if "." in text and "e" not in text.lower() else 6
                assert float(text) == pytest.approx(value, rel=1e-6, abs=max(1e-4, 0.5 * 10.0**-decimals + 1e-9)) or (
                    math.isinf(value) and text == "inf"), key
            else:
                assert text == value, key
    with open(tmp_path / "py" / "results.csv") as a, open(tmp_path / "cli" / "results.csv") as b:
        assert a.read() == b.read()


# ---- compare ----

def test_compare_equals_tfu_compare(cli, tmp_path):
    a, _ = tfu.render("ground_plane", width=64, height=48, filter="bilinear")
    b, _ = tfu.render("ground_plane", width=64, height=48, filter="trilinear")
    Image.fromarray(a, "RGBA").save(tmp_path / "a.png")
    Image.fromarray(b, "RGBA").save(tmp_path / "b.png")
    cli.run("compare", tmp_path / "a.png", tmp_path / "b.png", "--json", tmp_path / "m.json")
    want = read_json(tmp_path / "m.json")
    got = tfu.compare(a, b)
    for key in ("mse", "psnr_db", "ssim"):
        assert got[key] == pytest.approx(want[key], rel=1e-12), key
    assert got == tfu.compare(str(tmp_path / "a.png"), str(tmp_path / "b.png"))


def test_sweep_from_a_dict_is_the_same_spec_as_its_file(tmp_path):
    spec = {"scenes": ["ground_plane"], "filters": ["trilinear"], "width": 32, "height": 24,
            "grid": {"cache.capacity_bytes": [2048, 8192]}}
    rows = tfu.sweep(spec, str(tmp_path / "dict"))
    assert read_json(tmp_path / "dict" / "spec.json") == spec
    again = tfu.sweep(str(tmp_path / "dict" / "spec.json"), str(tmp_path / "file"))
    assert rows == again and [r["cache.capacity_bytes"] for r in rows] == [2048, 8192]
    assert all(r["golden_equal"] and r["filter"] == "LINEAR_MIPMAP_LINEAR" for r in rows)
    assert rows[1]["bytes_per_pixel"] <= rows[0]["bytes_per_pixel"]  # a larger cache reads no more
