"""fuzzygait_dask: trainings and walks on a local Dask cluster, against the same in-process."""
import json
import os
import subprocess
import sys

import pytest

import fuzzygait as fg
from conftest import SOURCE_DIR

distributed = pytest.importorskip("distributed", reason="Debian's python3-distributed")
import fuzzygait_dask as fgd  # noqa: E402  (after the skip: it needs distributed)

CLIPS = [SOURCE_DIR / "data" / "mocap" / "cmu" / f"{name}.bvh" for name in ("07_01", "08_01")]
OPTIONS = {"generations": 2, "polish": 1, "fit_iterations": 2, "threads": 1, "seed": 7}


@pytest.fixture(scope="module")
def client():
    # Worker processes inherit this process's environment: PYTHONPATH finds both modules.
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as c:
            yield c


@pytest.fixture
def truncated_clip(tmp_path):
    bad = tmp_path / "cut.bvh"
    bad.write_bytes(CLIPS[0].read_bytes()[:3000])  # ends inside the hierarchy
    return bad


def in_process_files(clip, tmp_path):
    t = fg.train([clip], **OPTIONS)
    t.set.save(tmp_path / clip.stem)
    return fgd.read_files(tmp_path / clip.stem), t


def test_clips_train_on_workers_as_in_process_and_a_bad_clip_fails_alone(
        client, truncated_clip, tmp_path):
    events = []
    results = fgd.train_clips([CLIPS[0], truncated_clip, CLIPS[1]], client,
                              progress=events.append, every=0.0, retries=1, **OPTIONS)
    assert [r.clip for r in results] == ["07_01", "cut", "08_01"]
    good = [results[0], results[2]]
    assert all(r.ok and r.worker.startswith("tcp://") for r in good)
    for clip, r in zip(CLIPS, good):
        files, t = in_process_files(clip, tmp_path)
        assert "manifest.json" in files and len(files) > 10
        assert r.files == files  # bit for bit
        assert (r.cost_before, r.cost_after) == (t.cost_before, t.cost_after)
        assert r.after[0]["knee"] == t.after[0]["knee"]
        assert r.after[0]["report"] == json.loads(t.after[0]["report"].to_json())
        assert [s["stage"] for s in r.stages] == [s["stage"] for s in t.stages]
        assert json.dumps(r.summary())  # JSON-ready
    bad = results[1]
    assert not bad.ok and not bad.files
    assert bad.error.startswith(f"ParseError: {truncated_clip}:")
    ends = [e for e in events if e["event"] != "iteration"]
    assert sorted(e["clip"] for e in ends) == ["07_01", "08_01", "cut"]
    assert [e["done"] for e in ends] == [1, 2, 3] and {e["total"] for e in ends} == {3}
    failed = [e for e in ends if e["event"] == "failed"]
    assert len(failed) == 1 and failed[0]["path"] == str(truncated_clip)
    assert any(e["event"] == "iteration" and e["clip"] == "07_01" for e in events)
    assert fg.ControllerSet.load(good[0].save(tmp_path / "saved")).body is not None


def test_a_missing_clip_fails_by_its_name_without_reaching_a_worker(client, tmp_path):
    [r] = fgd.train_clips([tmp_path / "none.bvh"], client, **OPTIONS)
    assert not r.ok and r.error.startswith("FileNotFoundError") and "none.bvh" in r.error


def test_a_set_walks_a_speed_stature_grid_on_workers_as_in_process(client):
    walks = fgd.grid([1.0, 1.4], [1.6, 1.9])
    assert len(walks) == 4 and walks[0] == {"speed": 1.0, "stature": 1.6}
    results = fgd.walk_many("default", walks, client, cycles=4)
    for walk, r in zip(walks, results):
        assert r["ok"] and r["speed"] == walk["speed"] and r["stature"] == walk["stature"]
        here = fg.evaluate(fg.Walker("default", **walk).record_cycles(4))
        assert r["report"] == json.loads(here.to_json())
        assert r["missed"] == here.missed_contact_bounds()


def test_a_walk_that_stalls_fails_alone_and_the_others_return(client):
    # The default stalls on 0.20 x 0.28 m stairs (record_cycles raises RuntimeError): should it
    # learn to climb them, pick a ground it stalls on.
    walks = [{"speed": 1.2}, {"speed": 1.2, "ground": "stairs:0.20:0.28:6"}, {"speed": 1.5}]
    results = fgd.walk_many("default", walks, client, cycles=4)
    assert [r["ok"] for r in results] == [True, False, True], [r.get("error") for r in results]
    assert results[1]["error"].startswith("RuntimeError: the walker did not complete 4 cycles")
    bad = fgd.walk_many("default", [{"speed": 1.2, "stride": 2}], client, cycles=4)
    assert not bad[0]["ok"] and "unknown option 'stride'" in bad[0]["error"]


def test_the_command_line_trains_prints_a_table_and_names_the_failed_clip(
        truncated_clip, tmp_path):
    out = tmp_path / "out"
    done = subprocess.run(
        [sys.executable, "-m", "fuzzygait_dask", "train", "--local-workers", "2", "--out", out,
         "--generations", "2", "--polish", "1", "--fit-iterations", "2", "--threads", "1",
         "--seed", "7", CLIPS[0], truncated_clip],
        capture_output=True, text=True, env=os.environ, timeout=120)
    assert done.returncode == 1, done.stderr
    lines = done.stdout.splitlines()
    assert "fuzzygait_dask: 2 clips on 2 workers" in lines
    assert any(line.startswith("[") and "07_01 trained in" in line for line in lines)
    table = lines[lines.index(next(x for x in lines if x.startswith("clip "))):]
    assert table[0].split()[:4] == ["clip", "status", "cost", "before"]
    assert table[1].split()[:2] == ["07_01", "ok"]
    assert table[2].split()[:3] == ["cut", "FAILED", "ParseError:"]
    assert f"1 of 2 clips failed: {truncated_clip}" in done.stderr
    files, _ = in_process_files(CLIPS[0], tmp_path)
    assert fgd.read_files(out / "07_01") == dict(files, **{
        "training.json": (out / "07_01" / "training.json").read_bytes()})
    assert json.loads((out / "07_01" / "training.json").read_text())["clip"] == "07_01"
    assert not (out / "cut").exists()


def test_a_leg_mapping_and_a_base_folder_travel_as_bytes(client, tmp_path):
    legs = tmp_path / "legs.json"
    legs.write_text(json.dumps({
        "root": "Hips",
        "left": {"hip": "LeftUpLeg", "knee": "LeftLeg", "ankle": "LeftFoot", "toe": "LeftToeBase"},
        "right": {"hip": "RightUpLeg", "knee": "RightLeg", "ankle": "RightFoot",
                  "toe": "RightToeBase"}}))
    base = tmp_path / "base"
    fg.ControllerSet.builtin("heavy").save(base)
    [r] = fgd.train_clips([CLIPS[0]], client, base=base, map=legs, **OPTIONS)
    t = fg.train([CLIPS[0]], fg.ControllerSet.load(base), map=legs, **OPTIONS)
    t.set.save(tmp_path / "here")
    assert r.ok and r.files == fgd.read_files(tmp_path / "here")
    legs.write_text('{"left": {"hip": "nowhere"}}')
    [bad] = fgd.train_clips([CLIPS[0]], client, map=legs, **OPTIONS)
    assert not bad.ok and "legs.json" in bad.error and str(tmp_path / "legs") not in bad.error
