"""What the Python tests share: the build's programs and the source tree (set by CTest)."""
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ["FUZZYGAIT_SOURCE_DIR"])
CLI = os.environ["FUZZYGAIT_CLI"]
WALK_BITS = os.environ["FUZZYGAIT_WALK_BITS"]
BODY_BITS = os.environ["FUZZYGAIT_BODY_BITS"]
CLIP = SOURCE_DIR / "data" / "mocap" / "cmu" / "07_01.bvh"


def run(*args, **kwargs):
    """Runs a program, returning its standard output; fails the test with its standard error."""
    done = subprocess.run([str(a) for a in args], capture_output=True, text=True, **kwargs)
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.fixture(scope="session")
def cli_walk(tmp_path_factory):
    """`fuzzygait walk` of the default (10 cycles at 120 frames a second): its CSV's text."""
    prefix = tmp_path_factory.mktemp("cli") / "walk"
    run(CLI, "walk", "-o", prefix)
    return (prefix.parent / "walk.csv").read_text()
