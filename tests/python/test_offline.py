"""Recorded motion, evaluation against normative curves, clips and training from Python."""
import json
import os
import signal

import numpy as np
import pytest

import fuzzygait as fg
from conftest import CLIP, SOURCE_DIR


@pytest.fixture(scope="module")
def default_walk():
    return fg.Walker().record_cycles(10)


def test_a_recorded_walk_has_its_frames_as_arrays(default_walk):
    m = default_walk
    n = len(m)
    assert m.fps == 120 and not m.captured and n > 1000
    assert m.times.shape == (n,) and m.times[1] == 1 / 120
    assert m.angles.shape == (n, 2, 4) and m.pelvis.shape == (n, 2)
    assert m.points.shape == (n, 2, 6, 2) and m.contact.shape == (n, 2)
    assert m.contact.dtype == bool and m.contact.any() and not m.contact.all()


def test_the_default_evaluates_within_the_readmes_bounds(default_walk):
    r = fg.evaluate(default_walk)
    assert r.cycles >= 9
    assert r.scores["knee"]["rmse"] <= 8 and r.scores["knee"]["pearson"] >= 0.9
    assert r.scores["thigh"]["rmse"] <= 6 and r.scores["ankle"]["rmse"] <= 6
    assert 57 <= r.stance_percent <= 65
    assert abs(r.step_error_percent) <= 3
    assert r.missed_contact_bounds() == []
    assert r.curves["knee"]["mean"].shape == (51,)
    d = r.to_dict()
    assert d["stance_percent"] == r.stance_percent and d["cycles"] == r.cycles
    assert len(d["smoothness"]) == 4
    as_json = json.loads(r.to_json())
    assert as_json["cycles"] == r.cycles
    assert "stance" in r.to_text()
    assert repr(r).startswith(f"<fuzzygait.GaitReport of {r.cycles} cycles: cadence ")
    assert repr(default_walk) == f"<fuzzygait.Motion of {len(default_walk)} frames at 120 fps>"
    bare = fg.evaluate(default_walk, reference=None, step=0.5)
    assert bare.scores["knee"] is None and bare.step_error_percent > 30
    assert "schwartz2008_free" in fg.normative_names()


def test_a_walk_is_recorded_for_a_time_on_its_ground_and_measured_against_a_file():
    ramp = fg.Terrain.ramp(5.0)
    motion = fg.Walker("default", ground=ramp).record(2.0, fps=60)
    assert len(motion) == 121 and motion.times[-1] == 2.0 and motion.ground is ramp
    long_walk = fg.Walker().record(12.0)
    curves = SOURCE_DIR / "data" / "normative" / "schwartz2008_sagittal_slow.csv"
    slow = fg.evaluate(long_walk, reference=str(curves))
    free = fg.evaluate(long_walk)
    assert slow.scores["knee"]["rmse"] != free.scores["knee"]["rmse"]
    with pytest.raises(ValueError, match="fewer than two complete gait cycles"):
        fg.evaluate(motion)


def test_a_walk_goes_to_csv_and_bvh_and_back(default_walk, tmp_path):
    default_walk.write_csv(tmp_path / "walk.csv")
    default_walk.write_bvh(tmp_path / "walk.bvh")
    back = fg.Motion.read_csv(tmp_path / "walk.csv")
    assert len(back) == len(default_walk) and back.commanded_step is None
    assert np.allclose(back.pelvis, default_walk.pelvis, atol=1e-6)
    assert (tmp_path / "walk.bvh").read_text().startswith("HIERARCHY")
    clip = fg.read_clip(tmp_path / "walk.bvh")
    assert len(clip.motion) == len(default_walk)


def test_a_clip_is_read_and_measured():
    clip = fg.read_clip(CLIP)
    assert clip.name == "07_01" and clip.unit == "CMU" and clip.up in ("y", "z")
    assert 90 < clip.cadence < 130 and 0.5 < clip.step_length < 0.8 and clip.speed > 0.8
    assert clip.motion.captured and len(clip.motion) > 200 and clip.cycles
    assert clip.metres_per_unit > 0 and clip.skipped_frames in (0, 1)
    assert all(isinstance(note, str) for note in clip.notes)
    assert repr(clip).startswith("<fuzzygait.Clip '07_01': ")
    report = fg.evaluate(clip.motion)
    assert report.cycles >= 1 and 50 < report.stance_percent < 70


def test_files_that_cannot_be_read_raise_parse_errors_naming_file_and_line(tmp_path):
    bvh = tmp_path / "bad.bvh"
    bvh.write_text("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 zero\n")
    with pytest.raises(fg.ParseError) as caught:
        fg.read_clip(bvh)
    assert caught.value.line == 4 and caught.value.source == str(bvh)
    assert str(caught.value).startswith(f"{bvh}:4:")
    with pytest.raises(ValueError, match="up must be 'y' or 'z'"):
        fg.read_clip(CLIP, up="x")
    csv = tmp_path / "bad.csv"
    csv.write_text("time,pelvis_x\n0,1\n")
    with pytest.raises(fg.ParseError, match="bad.csv"):
        fg.Motion.read_csv(csv)


def test_training_on_a_clip_gives_a_set_that_walks_and_saves(tmp_path):
    seen = []
    t = fg.train([CLIP], "default", name="mine", generations=2, polish=1, fit_iterations=2,
                 progress=seen.append)
    assert t.set.name == "mine" and t.set.body is not None
    assert t.set.body_step_length == pytest.approx(fg.read_clip(CLIP).step_length, rel=0.2)
    assert {s["stage"] for s in t.stages} >= {"commands", "polish"}
    assert len(t.before) == len(t.after) == 1 and t.before[0]["walked"]
    assert t.cost_after <= t.cost_before and not t.stopped
    assert seen and {"stage", "iteration", "cost", "rmse"} <= set(seen[0])
    t.set.save(tmp_path / "mine")
    again = fg.ControllerSet.load(tmp_path / "mine")
    assert again.name == "mine" and again.body == pytest.approx(t.set.body, abs=1e-4)
    w = fg.Walker(again)
    assert w.step_length == pytest.approx(t.set.body_step_length, abs=1e-4)
    assert w.segments == again.body  # a trained set walks its own body and step unless told
    assert fg.Walker(again, stature=1.7).segments == fg.segments_from_stature(1.7)
    assert fg.Walker(again, step_length=0.6).step_length == pytest.approx(0.6)
    w.advance(2.0)
    assert w.pelvis[0] > 1.0


def test_ctrl_c_stops_training_with_the_best_set_so_far():
    def interrupt(progress):
        if progress["stage"] == "polish":
            os.kill(os.getpid(), signal.SIGINT)

    t = fg.train([CLIP], generations=100000, polish=0, fit_iterations=1, progress=interrupt)
    assert t.stopped and t.set.name == "trained"
    assert np.isfinite(t.cost_after)


def test_training_options_are_checked_and_progress_errors_raise():
    with pytest.raises(ValueError, match="threads must be between 1 and 1024, got 0"):
        fg.train([CLIP], threads=0)
    with pytest.raises(ValueError, match="steps_around"):
        fg.train([CLIP], steps_around=[5.0])
    with pytest.raises(ValueError, match="unit must be metres per unit"):
        fg.train([CLIP], unit=0.0)
    with pytest.raises(fg.ParseError, match="07_01.bvh"):
        fg.train([CLIP], skip=100000)

    def fail(progress):
        raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        fg.train([CLIP], generations=2, polish=0, fit_iterations=1, progress=fail)
