# The module's exceptions carry the command line's one-line messages for the same bad inputs.
import os

import pytest

import tfu
from conftest import data


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
