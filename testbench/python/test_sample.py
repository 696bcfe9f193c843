# The module's golden sampler, textures (files, procedural, numpy arrays) and descriptors against
# `tfu sample` on the same inputs.
import numpy as np
import pytest
from PIL import Image

import tfu
from conftest import cli_samples, data


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
    assert tfu.texture_keys() == ["format", "mipmaps", "alpha", "layout", "tile_bytes", "compress", "srgb"]
