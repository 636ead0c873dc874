"""examples/walk_in_python.py and walk_a_path.py run and write what they say."""
import sys

import numpy as np

from conftest import SOURCE_DIR, run


def test_the_example_walks_measures_and_writes_the_walk(tmp_path):
    out = run(sys.executable, SOURCE_DIR / "examples" / "walk_in_python.py", tmp_path / "walk")
    assert "steps/min" in out and "knee: RMSE" in out and "a crowd of 100 walked 5 s" in out
    assert (tmp_path / "walk.csv").read_text().startswith("time,pelvis_x")
    assert (tmp_path / "walk.bvh").read_text().startswith("HIERARCHY")


def test_the_path_example_walks_a_skeleton_round_the_s(tmp_path):
    out = run(sys.executable, SOURCE_DIR / "examples" / "walk_a_path.py",
              SOURCE_DIR / "data" / "mocap" / "cmu" / "07_01.bvh", tmp_path / "path.npz")
    assert "left foot planted" in out and "path end (3.00, 6.00) reached" in out
    frames = np.load(tmp_path / "path.npz")
    count = len(frames["root"])
    assert frames["positions"].shape == (count, 26, 3) and frames["local"].shape == (count, 31, 4)
    assert np.abs(frames["positions"][-1, 0, [0, 2]] - [3, 6]).max() < 0.2
