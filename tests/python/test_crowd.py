"""A crowd from Python: its state arrays are views of the crowd's own memory, not copies."""
import gc

import numpy as np
import pytest

import fuzzygait as fg

PEOPLE = [{"step_length": 0.6}, {"speed": 1.4, "stature": 1.9}, {"seed": 3}]


def test_the_crowds_arrays_are_read_only_views_that_keep_it_alive():
    crowd = fg.Crowd("default", PEOPLE)
    angles = crowd.angles
    assert angles.shape == (3, 2, 4) and angles.dtype == np.float64
    assert angles.base is crowd
    assert np.shares_memory(angles, crowd.angles)
    assert not angles.flags.writeable and not angles.flags.owndata
    with pytest.raises(ValueError):
        angles[0, 0, 0] = 1.0
    pelvis = fg.Crowd("default", 2).pelvis  # the only reference to its crowd
    gc.collect()
    assert isinstance(pelvis.base, fg.Crowd) and len(pelvis.base) == 2
    pelvis.base.advance(0.5)
    assert pelvis[0, 0] == pelvis.base.pose(0)["pelvis"][0]


def test_stepping_the_crowd_changes_its_arrays_in_place():
    crowd = fg.Crowd("default", PEOPLE)
    views = {name: getattr(crowd, name) for name in
             ("angles", "velocities", "pelvis", "pelvis_tilt", "time", "speed", "phases")}
    before = {name: v.copy() for name, v in views.items()}
    for _ in range(30):
        assert crowd.advance(1 / 60)
    assert views["time"][0] == pytest.approx(0.5) and np.all(views["time"] == views["time"][0])
    for name in ("angles", "velocities", "pelvis"):
        assert not np.array_equal(views[name], before[name]), name
    for i in range(len(crowd)):
        pose = crowd.pose(i)
        assert np.array_equal(views["angles"][i], pose["angles"])
        assert np.array_equal(views["pelvis"][i], pose["pelvis"])
        assert views["pelvis_tilt"][i] == pose["pelvis_tilt"]
    assert views["phases"].dtype == np.uint8 and views["phases"].max() < len(fg.PHASES)
    events = crowd.events(0)
    assert events and set(events[0]) == {"time", "side", "event", "where"}
    crowd.clear_events()
    assert crowd.events(0) == []
    assert repr(crowd) == "<fuzzygait.Crowd of 3 with 'default'>"


def test_each_character_walks_as_a_lone_walker_bit_for_bit():
    crowd = fg.Crowd("default", PEOPLE)
    walkers = [fg.Walker("default", **p) for p in PEOPLE]
    for _ in range(120):
        crowd.advance(1 / 60)
        for w in walkers:
            w.advance(1 / 60)
    points = crowd.points()
    assert points.shape == (3, 2, 6, 2)
    for i, w in enumerate(walkers):
        assert np.array_equal(crowd.angles[i], w.angles)
        assert np.array_equal(crowd.velocities[i], w.velocities)
        assert np.array_equal(crowd.pelvis[i], w.pelvis)
        assert np.array_equal(points[i], w.points)
        assert tuple(fg.PHASES[p] for p in crowd.phases[i]) == w.phases


def test_a_crowd_on_two_threads_walks_the_same_bits():
    people = [{"step_length": 0.5 + 0.001 * i} for i in range(300)]  # three runs of blocks
    one = fg.Crowd("default", people)
    two = fg.Crowd("default", people, threads=2)
    assert one.workers == 1 and two.workers == 2
    for _ in range(60):
        one.advance(1 / 60)
        two.advance(1 / 60)
    assert np.array_equal(one.angles, two.angles)
    assert np.array_equal(one.pelvis, two.pelvis)


def test_crowd_commands_and_errors():
    crowd = fg.Crowd("heavy", 4, ground="slope:5")
    assert len(crowd) == 4 and crowd.batched_controllers
    assert crowd.set_step_length(1, 0.6) == pytest.approx(0.6)
    assert np.isnan(crowd.set_speed(9, 1.0))
    assert not crowd.advance(float("nan"))
    with pytest.raises(IndexError, match="character 4 of a crowd of 4"):
        crowd.pose(4)
    with pytest.raises(ValueError, match="character 1: unknown option 'pace'"):
        fg.Crowd("default", [{}, {"pace": 1.0}])
    with pytest.raises(TypeError, match="character 0 must be a dict of Walker options, not int"):
        fg.Crowd("default", [3])
    for none in (0, -2, []):
        with pytest.raises(ValueError, match="at least 1"):
            fg.Crowd("default", none)
