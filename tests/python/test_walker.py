"""Sets, grounds and a walker from Python: the walk is the C++ walk, bit for bit."""
import json
import math

import numpy as np
import pytest

import fuzzygait as fg
from conftest import SOURCE_DIR, WALK_BITS, run


def walker_state(w):
    """The numbers python_walk_bits prints for a walker's state, in its order."""
    values = [w.time, *w.pelvis, w.pelvis_tilt]
    for angles, velocities in zip(w.angles, w.velocities):
        values += [*angles, *velocities]
    return values


@pytest.mark.parametrize("speed", [None, 1.3])
def test_a_python_walk_is_the_cpp_walk_bit_for_bit(speed):
    frames = 360
    args = [WALK_BITS, "default", frames] + ([speed] if speed else [])
    expected = [[float.fromhex(v) for v in line.split()] for line in run(*args).splitlines()]
    w = fg.Walker(speed=speed)
    walked = [walker_state(w)]
    for _ in range(frames):
        assert w.advance(1 / 120)
        walked.append(walker_state(w))
    assert len(walked) == len(expected) == frames + 1
    for i, (mine, theirs) in enumerate(zip(walked, expected)):
        assert mine == theirs, f"frame {i}"


def csv_row(time, w):
    """A row of the walk CSV as io::write_walk_csv writes it (rig::degrees is x * (180 / pi))."""
    degrees = 180.0 / math.pi
    cells = [f"{time:.6f}", f"{w.pelvis[0]:.6f}", f"{w.pelvis[1]:.6f}",
             f"{w.pelvis_tilt * degrees:.4f}"]
    cells += [f"{a * degrees:.4f}" for a in w.angles.ravel()]
    cells += ["1" if c else "0" for c in w.in_contact]
    cells += [f"{v:.6f}" for v in w.points.ravel()]
    return ",".join(cells)


def test_stepped_in_python_the_default_writes_the_cli_walks_csv(cli_walk):
    rows = cli_walk.splitlines()[1:]
    w = fg.Walker()
    for i, row in enumerate(rows):
        if i > 0:
            w.advance(1 / 120)
        assert csv_row(i / 120, w) == row, f"frame {i}"


def test_recorded_the_default_writes_the_cli_walks_csv_byte_for_byte(cli_walk):
    motion = fg.Walker().record_cycles(10, fps=120)
    assert motion.to_csv() == cli_walk
    assert motion.commanded_step == 0.70


def test_the_same_walker_walks_the_same_and_random_starts_follow_their_seed():
    def walk(**options):
        w = fg.Walker(**options)
        for _ in range(100):
            w.advance(1 / 60)
        return np.concatenate([w.angles.ravel(), w.points.ravel(), w.pelvis])

    assert np.array_equal(walk(), walk())
    assert np.array_equal(walk(seed=7), walk(seed=7))
    assert not np.array_equal(walk(seed=7), walk(seed=8))


def test_the_module_has_a_version():
    assert fg.__version__.count(".") == 2


def test_sets_load_built_in_by_name_and_from_a_folder():
    names = fg.ControllerSet.builtin_names()
    assert {"default", "energetic", "heavy", "cautious"} <= set(names)
    heavy = fg.ControllerSet.builtin("heavy")
    assert heavy.name == "heavy" and heavy.cadence > 0 and heavy.body is None
    folder = fg.ControllerSet.load(SOURCE_DIR / "controllers" / "default")
    assert folder.name == "default"
    by_name, by_folder = fg.Walker("default"), fg.Walker(folder)
    by_path = fg.Walker(SOURCE_DIR / "controllers" / "default")
    for w in (by_name, by_folder, by_path):
        w.advance(1.0)
    assert np.array_equal(by_name.angles, by_folder.angles)
    assert np.array_equal(by_name.angles, by_path.angles)
    assert by_folder.set is folder


def test_a_sets_manifest_numbers_read_back_by_key(tmp_path):
    numbers = fg.ControllerSet.builtin("default").numbers
    assert numbers["cadence_steps_per_min"] == pytest.approx(110.0)
    assert numbers["first_step_share"] == pytest.approx(0.8)
    assert numbers["settle_rate_per_s"] == pytest.approx(7.0)
    folder = tmp_path / "brisk"
    folder.mkdir()
    for f in (SOURCE_DIR / "controllers" / "default").iterdir():
        (folder / f.name).write_text(f.read_text())
    manifest = json.loads((folder / "manifest.json").read_text())
    manifest["first_step_share"] = 0.95
    (folder / "manifest.json").write_text(json.dumps(manifest))
    brisk = fg.ControllerSet.load(folder)
    assert brisk.numbers["first_step_share"] == pytest.approx(0.95)
    assert brisk.numbers["inertia_s"] == pytest.approx(numbers["inertia_s"])


def test_a_walker_walks_forward_and_shows_its_pose_points_contacts_and_events():
    w = fg.Walker("energetic", step_length=0.65, stature=1.6)
    assert w.step_length == pytest.approx(0.65)
    assert w.segments == fg.segments_from_stature(1.6)
    start = w.pelvis.copy()
    w.advance(3.0)
    assert w.time == pytest.approx(3.0)
    assert w.pelvis[0] - start[0] > 2.0
    assert w.angles.shape == (2, 4) and w.angles.dtype == np.float64
    assert w.points.shape == (2, 6, 2)
    pose = w.pose()
    assert np.array_equal(pose["angles"], w.angles) and pose["pelvis_tilt"] == w.pelvis_tilt
    assert all(isinstance(c, bool) for c in w.in_contact)
    assert set(w.phases) <= set(fg.PHASES)
    events = w.events()
    assert {"heel strike", "toe off"} <= {e["event"] for e in events}
    assert {e["side"] for e in events} == {"left", "right"}
    w.clear_events()
    assert w.events() == []
    assert repr(w) == "<fuzzygait.Walker with 'energetic' at 3.000 s>"


def test_a_walker_walks_by_speed_and_its_commands_clamp():
    w = fg.Walker(speed=1.2)
    assert w.speed == pytest.approx(1.2)
    assert w.set_speed(100.0) == w.max_speed
    assert w.set_step_length(0.1) == w.min_step_length
    assert not w.advance(float("nan"))
    assert not w.advance(-1.0)


def test_a_walker_keeps_its_last_events_up_to_its_capacity():
    every, two, none = (fg.Walker(event_capacity=n) for n in (64, 2, 0))
    for w in (every, two, none):
        w.advance(2.0)
    assert len(every.events()) > 2
    assert [(e["time"], e["event"], e["side"]) for e in two.events()] == [
        (e["time"], e["event"], e["side"]) for e in every.events()[-2:]
    ]
    assert none.events() == []
    assert np.array_equal(none.angles, every.angles)
    with pytest.raises(ValueError, match="event capacity must be at most 4096"):
        fg.Walker(event_capacity=5000)
    with pytest.raises(TypeError, match="event_capacity must be a whole number"):
        fg.Walker(event_capacity=-1)


def test_slopes_and_stairs_are_walked_from_a_spec_or_points():
    w = fg.Walker(ground="slope:10")
    w.advance(4.0)
    assert w.pelvis[1] > w.ground.height(0.0) + 0.8
    stairs = fg.Terrain.from_spec("stairs:0.17:0.28:4")
    assert stairs.points.shape[1] == 2
    assert fg.Terrain.stairs(0.17, 0.28, 4).height(10.0) == pytest.approx(4 * 0.17)
    assert fg.Terrain.flat().height(123.0) == 0.0
    line = fg.Terrain.polyline(np.array([[-10.0, 0.0], [10.0, 0.5]]))
    assert line.height(0.0) == pytest.approx(0.25)


def test_bad_options_raise_value_errors_with_the_librarys_words():
    with pytest.raises(ValueError, match="stature must be between 0.5 and 3.0 m"):
        fg.Walker(stature=0.1)
    with pytest.raises(ValueError, match="not both"):
        fg.Walker(step_length=0.7, speed=1.2)
    with pytest.raises(ValueError, match="unknown option 'stride'"):
        fg.Walker(stride=0.7)
    with pytest.raises(ValueError, match="step"):
        fg.Walker(step_length=0.1)
    with pytest.raises(ValueError, match="unknown segment 'foot'"):
        fg.Walker(segments={"foot": 0.2})
    with pytest.raises(ValueError, match="thigh"):
        fg.Walker(segments={"thigh": -1.0})
    with pytest.raises(TypeError, match="step_length must be a number, not str"):
        fg.Walker(step_length="long")
    with pytest.raises(TypeError, match="seed must be a whole number"):
        fg.Walker(seed=-1)
    with pytest.raises(TypeError, match="segments must be a dict of segment lengths, not list"):
        fg.Walker(segments=[("thigh", 0.4)])
    with pytest.raises(ValueError, match="nosuchstyle"):
        fg.ControllerSet.builtin("nosuchstyle")
    with pytest.raises(ValueError, match="points must be an array of shape"):
        fg.Terrain.polyline(np.zeros(3))
    with pytest.raises(ValueError, match="--terrain|terrain"):
        fg.Terrain.from_spec("stairs:0.9:0.28:6")


def test_a_set_whose_file_is_broken_raises_a_parse_error_naming_file_and_line(tmp_path):
    folder = tmp_path / "broken"
    folder.mkdir()
    source = SOURCE_DIR / "controllers" / "default"
    for f in source.iterdir():
        (folder / f.name).write_text(f.read_text())
    knee = folder / "swing_knee.fll"
    lines = knee.read_text().splitlines()
    lines[3] = "  nonsense: here"
    knee.write_text("\n".join(lines) + "\n")
    with pytest.raises(fg.ParseError) as caught:
        fg.ControllerSet.load(folder)
    assert "swing_knee.fll" in str(caught.value)
    assert caught.value.line == 4 and "swing_knee.fll" in caught.value.source
    assert isinstance(caught.value, ValueError)


def test_a_walker_stops_on_the_spot_and_starts_again_from_standing():
    walker = fg.Walker("default", step_length=0.7)
    walker.advance(3.0)
    assert walker.locomotion == "walking"
    walker.stop()
    assert walker.locomotion == "stopping"
    walker.advance(3.0)
    assert walker.standing and walker.locomotion == "standing"
    heels = walker.points[:, 3, 0]  # [side, heel, x]
    assert abs(heels[0] - heels[1]) < 1e-3
    walker.go()
    assert walker.locomotion == "walking"
    x = walker.pelvis[0]
    walker.advance(3.0)
    assert walker.pelvis[0] - x > 2.5


def test_a_walker_made_standing_stands_until_go_and_crowds_stop_theirs():
    walker = fg.Walker("default", standing=True)
    assert walker.standing
    before = walker.pelvis.copy()
    walker.advance(1.0)
    assert np.array_equal(walker.pelvis, before)
    with pytest.raises(TypeError, match="standing must be True or False"):
        fg.Walker("default", standing="yes")
    crowd = fg.Crowd("default", [{"standing": True}, {}])
    assert crowd.standing(0) and not crowd.standing(1)
    assert crowd.go(0) and crowd.stop(1)
    assert not crowd.go(2)
    crowd.advance(3.0)
    assert not crowd.standing(0) and crowd.standing(1)
