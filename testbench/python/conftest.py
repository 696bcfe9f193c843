# The Python module's tests (docs/python.md) run under ctest as `/usr/bin/python3 -m pytest`
# (sim/python/CMakeLists.txt) with PYTHONPATH at build/python, TFU_BIN the tfu binary of the same
# build and TFU_SOURCE_DIR the source tree. Every test compares the module with the command line on
# the same inputs: the module calls the libraries the command line calls, so the values are equal.
import json
import os
import subprocess

import numpy as np
import pytest
from PIL import Image

TFU_BIN = os.environ.get("TFU_BIN", "")
SOURCE_DIR = os.environ.get("TFU_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
DATA = os.path.join(SOURCE_DIR, "testbench", "data")


class Cli:
    """Runs build/bin/tfu; returns (exit code, stdout, stderr)."""

    def run(self, *args, check=True):
        if not TFU_BIN:
            pytest.fail("TFU_BIN is not set (ctest passes the tfu binary of the build)")
        p = subprocess.run([TFU_BIN, *map(str, args)], capture_output=True, text=True)
        if check and p.returncode != 0:
            raise AssertionError(f"tfu {' '.join(map(str, args))}: exit {p.returncode}: {p.stderr}")
        return p.returncode, p.stdout, p.stderr

    def error_message(self, *args):
        """The one-line message of a failing command, without its "tfu: error: " prefix."""
        code, _, err = self.run(*args, check=False)
        assert code == 2, (code, err)
        line = err.strip()
        assert "\n" not in line and line.startswith("tfu: error: "), line
        return line[len("tfu: error: "):]


@pytest.fixture(scope="session")
def cli():
    return Cli()


def read_png(path):
    """An image file as the module returns images: H x W x 4 uint8 (RGBA)."""
    return np.asarray(Image.open(path).convert("RGBA"))


def read_json(path):
    with open(path) as f:
        return json.load(f)


def cli_samples(cli, *args):
    _, out, _ = cli.run("sample", *args, "--out", "-")
    return np.array([[int(v) for v in line.split(",")] for line in out.splitlines()], dtype=np.uint8)


def data(name):
    return os.path.join(DATA, name)
