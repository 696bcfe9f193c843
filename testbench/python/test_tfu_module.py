# The module `tfu` against the command line on the same inputs: golden samples, renders and their
# traces, the cycle model's statistics and pixels, sweeps' rows, image metrics, and the one-line
# error messages. Small inputs: the whole file runs in a few seconds.
import math
import os

import numpy as np
import pytest
from PIL import Image

import tfu
from conftest import data, read_json, read_png


def cli_samples(cli, *args):
    _, out, _ = cli.run("sample", *args, "--out", "-")
    return np.array([[int(v) for v in line.split(",")] for line in out.splitlines()], dtype=np.uint8)


# ---- sample: the golden model ----

def test_sample_trace_that_binds_its_textures(cli):
    got = tfu.sample(None, None, data("two_textures.txt"))
    want = cli_samples(cli, "--requests", data("two_textures.txt"))
    assert got.shape == (4, 4) and got.dtype == np.uint8
    np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("trace,filter", [("lod.txt", "trilinear"), ("quad.txt", "cubic"), ("grad_aniso.txt", "LINEAR_MIPMAP_LINEAR")])
def test_sample_texture_and_sampler(cli, trace, filter):
    keys = {"max_aniso": 8} if "aniso" in trace else {}
    got = tfu.sample(tfu.Texture("proc:zoneplate:64"), tfu.Sampler(filter=filter, wrap_s="mirrored-repeat", **keys),
                     tfu.Trace.load(data(trace)))
    flags = ["--max-aniso", "8"] if keys else []
    want = cli_samples(cli, "--texture", "proc:zoneplate:64", "--filter", filter, "--wrap-s", "mirrored-repeat", *flags,
                       "--requests", data(trace))
    np.testing.assert_array_equal(got, want)


def test_sample_numpy_arrays_equal_the_same_texels_from_files(cli, tmp_path):
    # An RGBA8 array and an L8 array give what the same texels written to PNG files give the CLI.
    rng = np.random.default_rng(7)
    rgba = rng.integers(0, 256, size=(24, 40, 4), dtype=np.uint8)
    lum = rng.integers(0, 256, size=(24, 40), dtype=np.uint8)
    Image.fromarray(rgba, "RGBA").save(tmp_path / "rgba.png")
    Image.fromarray(lum, "L").save(tmp_path / "lum.png")
    requests = np.array([[0.1, 0.2, 0.0], [0.33, 0.71, 0.6], [0.9, 0.05, 1.7], [0.5, 0.5, 3.2]], dtype=np.float32)
    trace = tfu.Trace(requests)
    assert trace.mode == "lod" and len(trace) == 4
    trace.save(str(tmp_path / "req.txt"))
    for array, png in ((rgba, "rgba.png"), (lum, "lum.png")):
        tex = tfu.Texture.from_array(array, mipmaps="gaussian")
        assert tex.format == ("l8" if array.ndim == 2 else "rgba8") and tex.levels == 6
        got = tfu.sample(tex, tfu.Sampler(filter="LINEAR_MIPMAP_LINEAR"), requests)
        want = cli_samples(cli, "--texture", tmp_path / png, "--mipmaps", "gaussian", "--filter", "LINEAR_MIPMAP_LINEAR",
                           "--requests", tmp_path / "req.txt")
        np.testing.assert_array_equal(got, want)
    # Level 0 of a texture made from an array is the array (L8 replicated into RGB, A = 255).
    np.testing.assert_array_equal(tfu.Texture.from_array(rgba).level(0), rgba)
    lum_words = tfu.Texture.from_array(lum).level(0)
    np.testing.assert_array_equal(lum_words[..., 0], lum)
    assert (lum_words[..., 3] == 255).all()


def test_vs16x2_numerators_pack_as_strzodka_pairs():
    # psi(h, l) = (256 (h - 128) + l) / 32640: numerator n is the byte pair of n + 32768.
    n = np.array([[[-32640, 32640], [0, 1]], [[-1, 255], [256, -256]]], dtype=np.int16)
    words = tfu.Texture.from_array(n, mipmaps="none").level(0)
    v = n.astype(np.int32) + 32768
    np.testing.assert_array_equal(words[..., 0], v[..., 0] >> 8)
    np.testing.assert_array_equal(words[..., 1], v[..., 0] & 255)
    np.testing.assert_array_equal(words[..., 2], v[..., 1] >> 8)
    np.testing.assert_array_equal(words[..., 3], v[..., 1] & 255)
    with pytest.raises(tfu.InputError, match="outside -32640..32640"):
        tfu.Texture.from_array(np.full((2, 2, 2), -32641, dtype=np.int16))


def test_descriptors_use_the_register_field_tables(cli):
    s = tfu.Sampler(filter="trilinear", wrap_t="clamp-to-edge", max_aniso=4)
    assert s.keys["filter"] == "LINEAR_MIPMAP_LINEAR" and s.keys["max_aniso"] == "4"
    words = s.registers()
    fields = s.descriptor()
    table = tfu.descriptor_fields("sampler")
    assert [f["name"] for f in table] == list(fields)
    for f in table:  # every field is its bits of its word
        if f["count"] == 1:
            assert fields[f["name"]] == (words[f["word"]] >> f["lsb"]) & ((1 << f["width"]) - 1)
    tex = tfu.Texture("proc:checkerboard:64")
    d = tex.descriptor()
    assert [f["name"] for f in tfu.descriptor_fields("texture")] == list(d)
    assert set(tfu.sampler_keys()) >= {"filter", "wrap_s", "wrap_t", "max_aniso"}
    assert tfu.texture_keys() == ["format", "mipmaps", "alpha", "layout", "tile_bytes", "compress"]


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
            if isinstance(value, bool):
                assert text == ("true" if value else "false")
            elif isinstance(value, (int, float)):
                assert float(text) == pytest.approx(value, rel=1e-6, abs=1e-4) or (math.isinf(value) and text == "inf"), key
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


# ---- errors: the command line's one-line messages ----

def test_errors_carry_the_cli_message(cli, tmp_path):
    cases = [
        (lambda: tfu.simulate("no_such_scene"), ("sim", "--scene", "no_such_scene")),
        (lambda: tfu.simulate("ground_plane", data("unit_bad_key.json")), ("sim", "--config", data("unit_bad_key.json"))),
        (lambda: tfu.simulate(tfu.Trace.load(data("trace_hex.txt"))), ("sim", "--requests", data("trace_hex.txt"))),
        (lambda: tfu.render("oa:aggressor:x"), ("render", "--scene", "oa:aggressor:x")),
        (lambda: tfu.sweep(data(os.path.join("sweep", "bad_key.json")), str(tmp_path / "s")),
         ("sweep", data(os.path.join("sweep", "bad_key.json")), "--out", tmp_path / "s2")),
    ]
    for call, args in cases:
        with pytest.raises(tfu.InputError) as e:
            call()
        assert isinstance(e.value, ValueError)
        assert str(e.value) == cli.error_message(*args)
    # A key's message is the flag's, under the key's name instead of the flag's.
    with pytest.raises(tfu.InputError) as e:
        tfu.Sampler(filter="trilinar")
    want = cli.error_message("sample", "--texture", "proc:checkerboard:64", "--filter", "trilinar", "--requests", data("lod.txt"),
                             "--out", "-")
    assert want.startswith("--filter: ") and str(e.value).startswith("sampler: key 'filter': ")
    a, b = (m.removesuffix("...") for m in (want[len("--filter: "):], str(e.value)[len("sampler: key 'filter': "):]))
    assert a.startswith(b) or b.startswith(a)  # equal up to where the longer prefix cuts the line
