# The module's renderer and cycle model against `tfu render` and `tfu sim` on the same inputs: images,
# trace files, statistics and pixels.
import numpy as np
import pytest

import tfu
from conftest import cli_samples, data, read_json, read_png


# ---- render: the golden renderer ----

def test_render_image_and_trace_equal_the_cli(cli, tmp_path):
    image, trace = tfu.render("ground_plane", width=64, height=48, filter="trilinear")
    cli.run("render", "--scene", "ground_plane", "--width", 64, "--height", 48, "--filter", "trilinear",
            "--out", tmp_path / "r.png", "--trace-out", tmp_path / "r.txt")
    assert image.shape == (48, 64, 4)
    np.testing.assert_array_equal(image, read_png(tmp_path / "r.png"))
    with open(tmp_path / "r.txt") as f:
        assert trace.text() == f.read()
    assert trace.mode == "quad" and len(trace) % 4 == 0 and trace.requests.shape == (len(trace), 2)
    # The render's trace through the golden model, and the trace file through tfu sample.
    np.testing.assert_array_equal(tfu.sample(None, None, trace), cli_samples(cli, "--requests", tmp_path / "r.txt"))


# ---- simulate: the cycle model with the golden compare ----

STATS_KEYS = ("counters", "values", "histograms", "tables", "definitions")


def assert_same_stats(got, want):
    for key in STATS_KEYS:
        assert got.get(key) == want.get(key), key
    g, w = dict(got["provenance"]), dict(want["provenance"])
    for p in (g, w):
        p.pop("command_line")
    assert g == w


def test_simulate_scene_equals_tfu_sim(cli, tmp_path):
    config = {"cache.capacity_bytes": 4096, "memory": {"latency": 50}}
    stats, pixels = tfu.simulate("lightmapped", config, width=96, height=64, filter="trilinear")
    cli.run("sim", "--scene", "lightmapped", "--width", 96, "--height", 64, "--filter", "trilinear", "--cache-bytes", 4096,
            "--latency", 50, "--stats", tmp_path / "s.json", "--out", tmp_path / "o.png")
    want = read_json(tmp_path / "s.json")
    assert_same_stats(stats, want)
    assert stats["golden_compare"] == "all equal"
    assert stats["provenance"]["unit_config"]["cache"]["capacity_bytes"] == 4096
    np.testing.assert_array_equal(pixels, read_png(tmp_path / "o.png"))
    # The render's trace simulated gives the same (the render is the one simulate makes itself).
    image, trace = tfu.render("lightmapped", width=96, height=64, filter="trilinear")
    stats2, pixels2 = tfu.simulate(trace, config)
    assert stats2["counters"] == stats["counters"]
    np.testing.assert_array_equal(pixels2, pixels)
    with pytest.raises(tfu.InputError, match="rendered for 64-byte cache lines"):
        tfu.simulate(trace, {"cache.line_bytes": 256})


def test_simulate_request_trace_equals_tfu_sim(cli, tmp_path):
    stats, pixels = tfu.simulate(tfu.Trace.load(data("two_textures.txt")), data("unit_config.json"))
    cli.run("sim", "--requests", data("two_textures.txt"), "--config", data("unit_config.json"), "--stats", tmp_path / "s.json")
    assert_same_stats(stats, read_json(tmp_path / "s.json"))
    np.testing.assert_array_equal(pixels, tfu.sample(None, None, data("two_textures.txt")))  # bit-exact: the golden outputs


def test_unit_config_fields_and_defaults(cli):
    fields = tfu.unit_config_fields()
    config = tfu.unit_config({f["key"]: f["default"] for f in fields})
    assert config == tfu.unit_config()
    _, md, _ = cli.run("sim", "--config-fields")
    for f in fields:
        assert f"`{f['key']}` | `{f['flag']}`" in md
