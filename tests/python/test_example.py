"""examples/walk_in_python.py runs and writes what it says."""
import sys

from conftest import SOURCE_DIR, run


def test_the_example_walks_measures_and_writes_the_walk(tmp_path):
    out = run(sys.executable, SOURCE_DIR / "examples" / "walk_in_python.py", tmp_path / "walk")
    assert "steps/min" in out and "knee: RMSE" in out and "a crowd of 100 walked 5 s" in out
    assert (tmp_path / "walk.csv").read_text().startswith("time,pelvis_x")
    assert (tmp_path / "walk.bvh").read_text().startswith("HIERARCHY")
