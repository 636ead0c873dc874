# The walk itself: a fuzzygait.Walker stepped frame by frame, and keyframes that put the mapped
# bones where its segments are.
#
# Each leg bone is turned from its rest orientation about the body's lateral axis, so that in
# the walking plane the thigh points from the walker's hip to its knee, the shin from knee to
# ankle, and the foot and toe pitch as the walker's sole and toes do (rest feet are taken as
# flat). This works from each bone's rest matrix, so any bone roll or local axes will do; a bone
# off the walking plane (legs splayed at rest) keeps its sideways part. The pelvis carries the
# body along the path (its location and heading) and, with a spine bone mapped, the walker's
# pelvic tilt while the spine stays upright; otherwise the trunk stays upright with the pelvis.
# Along a curve the straight walk is bent onto it: each joint goes to the curve's frame at its
# own distance along, so a planted foot stays planted while the hips turn.
import math
import os
import sys
from dataclasses import dataclass, field

import bpy
from mathutils import Matrix

from . import body as bodies
from . import path as paths
from . import rig

HIP_HEIGHT = 0.530  # hip joint height over stature (the library's proportions, Winter 2009)


class WalkError(Exception):
    """Settings or an armature the walk cannot use; the message says what to change."""


def import_module(extra_dirs=()):
    """The fuzzygait module: importable as it is, or from one of extra_dirs (tried in order).
    Raises WalkError saying where it was looked for."""
    try:
        import fuzzygait
        return fuzzygait
    except ImportError as error:
        first = error
    for folder in extra_dirs:
        if folder and os.path.isdir(folder) and folder not in sys.path:
            sys.path.append(folder)
            try:
                import fuzzygait
                return fuzzygait
            except ImportError:
                sys.path.remove(folder)
    raise WalkError("the fuzzygait Python module cannot be imported (%s); install it (cmake "
                    "--install) or set its folder in the add-on's preferences (looked in: %s)"
                    % (first, ", ".join(d for d in extra_dirs if d) or "sys.path only"))


@dataclass
class Settings:
    controllers: str = "default"    # a built-in set's name
    controller_folder: str = ""     # a set's folder; overrides controllers when given
    pace: str = "SPEED"             # SPEED or STEP
    speed: float = 1.3              # m/s
    step_length: float = 0.70       # m
    stature: float = 0.0            # m; 0: measured from the legs (1.75 if implausible)
    frame_start: int = 1
    frame_end: int = 250
    fps: float = 24.0
    path: str = "STRAIGHT"          # STRAIGHT or CURVE
    curve: object = None            # the curve object for CURVE
    pelvis_tilt: bool = True
    whole_body: bool = False        # the follower poses arms, trunk and legs (body.py)
    bones: dict = field(default_factory=dict)  # role -> bone name, "" automatic


@dataclass
class Result:
    bones: dict         # the bone map used
    stature: float     # the walker's stature, m
    scale: float       # world units per walker metre
    segments: dict     # the walker's segment lengths, m
    frames: int
    travel: float      # walker metres from the first frame to the last
    past_curve_end: bool = False


def _check_number(name, value, positive=True):
    if not isinstance(value, (int, float)) or not math.isfinite(value):
        raise WalkError("%s must be a finite number, not %r" % (name, value))
    if positive and value <= 0:
        raise WalkError("%s must be above 0, not %g" % (name, value))


def controller_set(fg, settings):
    folder = settings.controller_folder
    if folder:
        if not os.path.isdir(folder):
            raise WalkError("controller set folder '%s' does not exist" % folder)
        try:
            return fg.ControllerSet.load(folder)
        except (ValueError, RuntimeError) as error:
            raise WalkError("controller set folder '%s': %s" % (folder, error)) from None
    names = list(fg.ControllerSet.builtin_names())
    if settings.controllers not in names:
        raise WalkError("'%s' is not a built-in controller set (%s); give a folder for others"
                        % (settings.controllers, ", ".join(names)))
    return fg.ControllerSet.builtin(settings.controllers)


def _pace(settings):
    """The walker's pace option: {"speed": m/s} or {"step_length": m}."""
    if settings.pace == "SPEED":
        _check_number("speed", settings.speed)
        return {"speed": float(settings.speed)}
    if settings.pace == "STEP":
        _check_number("step length", settings.step_length)
        return {"step_length": float(settings.step_length)}
    raise WalkError("pace must be SPEED or STEP, not %r" % settings.pace)


def make_walker(fg, settings, measure, unit_scale):
    """(walker, stature m, armature units per walker metre)."""
    pace = _pace(settings)
    _check_number("stature", settings.stature, positive=False)
    if settings.stature < 0:
        raise WalkError("stature must be 0 (measured) or above, not %g" % settings.stature)
    stature = settings.stature
    if stature == 0:
        stature = measure.leg_length * unit_scale / HIP_HEIGHT
        if not 0.5 <= stature <= 3.0:
            stature = 1.75  # a rig in other units than the scene's: walk it as 1.75 m tall
    scale = measure.leg_length / (HIP_HEIGHT * stature)
    segments = {"thigh": measure.thigh / scale, "shank": measure.shank / scale,
                "ankle_height": measure.ankle_height / scale, "ball": measure.ball / scale}
    if measure.toe > 0:
        segments["toe"] = measure.toe / scale
    try:
        walker = fg.Walker(controller_set(fg, settings), stature=stature, segments=segments,
                           **pace)
    except (ValueError, TypeError) as error:
        raise WalkError("the walker cannot walk this armature: %s" % error) from None
    return walker, stature, scale


def _orientations(tilt, angles):
    """Per leg (thigh, shank inclinations, foot, toes pitches), radians (rig::orientation)."""
    result = []
    for hip, knee, ankle, toe in angles:
        thigh = hip - tilt
        shank = thigh - knee
        foot = shank + ankle
        result.append((thigh, shank, foot, foot + toe))
    return result


class Solver:
    """Armature-space pose matrices for the mapped bones, and their local (basis) matrices."""

    def __init__(self, armature_object, mapping, measure, use_tilt):
        self.obj = armature_object
        self.bones = armature_object.data.bones
        self.map = mapping
        self.m = measure
        self.use_tilt = use_tilt and bool(mapping["spine"])
        self.role = {name: key for key, name in mapping.items() if name}
        # The mapped bones and their ancestors, parents first.
        needed = set()
        for name in self.role:
            needed.add(name)
            needed.update(b.name for b in self.bones[name].parent_recursive)
        self.order = sorted(needed, key=lambda n: len(self.bones[n].parent_recursive))
        self.basis = {n: self.obj.pose.bones[n].matrix_basis.copy() for n in self.order}
        # Under the hips at rest, on the ground: where the walk starts as if straight.
        self.start = measure.hip - measure.up * (measure.hip.dot(measure.up) - measure.ground)
        # Each leg bone's next joint (the next bone's head, the toe's tail) in its rest space.
        self.end_local = {}
        for side in ("l", "r"):
            chain = [mapping[p + "_" + side] for p in ("thigh", "shin", "foot", "toe")]
            for name, after in zip(chain, chain[1:] + [""]):
                if not name:
                    continue
                bone = self.bones[name]
                end = self.bones[after].head_local if after else bone.tail_local
                self.end_local[name] = bone.matrix_local.inverted() @ end

    def _turns(self, tilt, angles, points):
        """{leg bone: its turn from rest about the lateral axis}, radians."""
        m = self.m
        orient = _orientations(tilt, angles)
        turn = {}
        for leg, side in enumerate(("l", "r")):
            hip, knee, ankle = (points[leg][j] for j in range(3))
            thigh = math.atan2(knee[0] - hip[0], hip[1] - knee[1])
            shank = math.atan2(ankle[0] - knee[0], knee[1] - ankle[1])
            names = [self.map[p + "_" + side] for p in ("thigh", "shin", "foot", "toe")]
            turn[names[0]] = thigh - m.rest_angle[names[0]]
            turn[names[1]] = shank - m.rest_angle[names[1]]
            turn[names[2]] = orient[leg][2]
            if names[3]:
                turn[names[3]] = orient[leg][3]
        return turn

    def _yaw(self, heading):
        """The turn about up from the rest facing to heading (4x4)."""
        m = self.m
        angle = math.atan2(m.forward.cross(heading).dot(m.up), m.forward.dot(heading))
        return Matrix.Rotation(angle, 4, m.up)

    def _warp(self, route, point):
        """A point of the walk as if straight (from self.start along the rest facing) carried to
        the route: by its distance along, its height and its sideways offset."""
        m = self.m
        d = point - self.start
        ground, heading = route.at(d.dot(m.forward))
        return ground + heading.cross(m.up) * d.dot(m.lateral) + m.up * d.dot(m.up)

    def pose(self, route, distance, height, tilt, angles, points, scale):
        """{bone name: basis matrix} for the mapped bones at one sample, the hips `distance`
        along the route. Along a curve the walk is posed as if straight, then bent along it:
        each leg bone points at its next joint carried to the route at that joint's own
        distance, so that a planted foot stays where it was planted."""
        m = self.m
        turn = self._turns(tilt, angles, points)

        def straight_leg(name, yaw, inherited):
            rest = self.bones[name].matrix_local.to_3x3()
            return yaw.to_3x3() @ Matrix.Rotation(turn[name], 3, m.lateral) @ rest

        ground, heading = route.at(distance)
        if isinstance(route, paths.StraightPath):
            return self._solve(ground, heading, height, tilt, scale, straight_leg)[1]
        straight = self._solve(self.start + m.forward * distance, m.forward, height, tilt, scale,
                               straight_leg)[0]

        def bent_leg(name, yaw, inherited):
            posed = straight[name]
            head, end = posed.translation, posed @ self.end_local[name]
            turn_here = self._yaw(route.at((head - self.start).dot(m.forward))[1]).to_3x3()
            was = turn_here @ (end - head)
            now = self._warp(route, end) - inherited.translation
            return was.rotation_difference(now).to_matrix() @ turn_here @ posed.to_3x3()

        return self._solve(ground, heading, height, tilt, scale, bent_leg)[1]

    def _solve(self, ground, heading, height, tilt, scale, orient_leg):
        """(armature-space pose matrices of the mapped bones and their ancestors, basis matrices
        of the mapped bones) with the hips `height` walker metres above ground, facing heading;
        orient_leg(name, yaw, inherited) gives a leg bone's orientation (3x3)."""
        m = self.m
        yaw = self._yaw(heading)
        body = Matrix.Translation(ground + m.up * (height * scale)) @ yaw
        posed, result = {}, {}
        for name in self.order:
            bone = self.bones[name]
            rest = bone.matrix_local
            parent = bone.parent
            # Where the bone would be with the parent as posed and its own basis unchanged.
            if parent is None:
                inherited = rest @ self.basis[name]
                local_rest = rest
            else:
                local_rest = parent.matrix_local.inverted() @ rest
                inherited = posed[parent.name] @ local_rest @ self.basis[name]
            role = self.role.get(name)
            if role == "pelvis":
                turn_pelvis = Matrix.Rotation(-tilt, 4, m.lateral) if self.use_tilt else Matrix()
                target = body @ turn_pelvis @ Matrix.Translation(-m.hip) @ rest
            elif role == "spine":
                target = self._rotated(inherited, yaw @ rest)
            elif role is not None:
                target = self._rotated(inherited, orient_leg(name, yaw, inherited).to_4x4())
            else:
                posed[name] = inherited
                continue
            posed[name] = target
            parent_posed = posed[parent.name] if parent else Matrix()
            result[name] = (parent_posed @ local_rest).inverted() @ target
        return posed, result

    @staticmethod
    def _rotated(inherited, oriented):
        """oriented's rotation with inherited's head position."""
        matrix = oriented.to_3x3().to_4x4()
        matrix.translation = inherited.translation
        return matrix


class Keys:
    """Keyframe values per (data path, index), written as F-curves in one go."""

    def __init__(self):
        self.values = {}

    def add(self, bone, prop, frame, vector):
        path = 'pose.bones["%s"].%s' % (bone.replace('"', '\\"'), prop)
        for i, v in enumerate(vector):
            self.values.setdefault((path, i, bone), []).append((frame, v))

    def write(self, obj, first, last, action_name):
        data = obj.animation_data or obj.animation_data_create()
        if data.action is None:
            data.action = bpy.data.actions.new(action_name)
        action = data.action
        for (path, index, group), keys in self.values.items():
            curve = action.fcurves.find(path, index=index)
            if curve is None:
                curve = action.fcurves.new(path, index=index, action_group=group)
            for point in reversed(list(curve.keyframe_points)):
                if first - 0.5 <= point.co.x <= last + 0.5:
                    curve.keyframe_points.remove(point, fast=True)
            for frame, value in keys:
                curve.keyframe_points.insert(frame, value, options={"FAST"})
            curve.update()


def _rotation_values(pose_bone, quaternion, previous):
    """(property, values) for the bone's rotation mode; continuous with previous."""
    mode = pose_bone.rotation_mode
    if mode == "QUATERNION":
        if previous is not None and previous.dot(quaternion) < 0:
            quaternion = -quaternion
        return "rotation_quaternion", quaternion, quaternion
    if mode == "AXIS_ANGLE":
        axis, angle = quaternion.to_axis_angle()
        return "rotation_axis_angle", (angle, *axis), None
    euler = quaternion.to_euler(mode, previous) if previous is not None else \
        quaternion.to_euler(mode)
    return "rotation_euler", euler, euler


def walk_armature(obj, settings, depsgraph, unit_scale=1.0, module_dirs=()):
    """Walks the armature object: keyframes on the mapped bones for every frame from
    settings.frame_start to frame_end. Raises WalkError (or its causes' messages) and then
    writes nothing."""
    if obj is None or obj.type != "ARMATURE":
        raise WalkError("no armature is active: select an armature object")
    _check_number("fps", settings.fps)
    if settings.frame_end < settings.frame_start:
        raise WalkError("the end frame %d is before the start frame %d"
                        % (settings.frame_end, settings.frame_start))
    try:
        mapping = rig.resolve_map(obj.data.bones, settings.bones)
        measure = rig.measure(obj, mapping)
    except rig.RigError as error:
        raise WalkError("armature '%s': %s" % (obj.name, error)) from None
    scale_vector = obj.matrix_world.to_scale()
    if max(scale_vector) - min(scale_vector) > 1e-4 * max(scale_vector):
        raise WalkError("armature '%s' is scaled unevenly (%s): apply its scale first"
                        % (obj.name, tuple(round(s, 4) for s in scale_vector)))
    object_scale = scale_vector[0]

    solver = Solver(obj, mapping, measure, settings.pelvis_tilt)
    points = None
    if settings.path == "STRAIGHT":
        route = paths.StraightPath(solver.start, measure.forward)
    elif settings.path == "CURVE":
        curve = settings.curve
        if curve is None or curve.type != "CURVE":
            raise WalkError("no curve to walk along: name a curve object or select one with the "
                            "armature")
        try:
            to_armature = obj.matrix_world.inverted()
            points = [to_armature @ p for p in paths.curve_points(curve, depsgraph)]
            route = paths.PolylinePath(points, measure.up)
        except paths.PathError as error:
            raise WalkError(str(error)) from None
    else:
        raise WalkError("path must be STRAIGHT or CURVE, not %r" % settings.path)

    fg = import_module(module_dirs)
    if settings.whole_body:
        return _walk_whole_body(fg, obj, settings, mapping, measure,
                                solver.start if points is None else points[0], points,
                                unit_scale * object_scale)
    walker, stature, scale = make_walker(fg, settings, measure, unit_scale * object_scale)
    keys = Keys()
    dt = 1.0 / settings.fps
    x0 = float(walker.pelvis[0])
    previous = {}
    past_end = False
    for frame in range(settings.frame_start, settings.frame_end + 1):
        if frame > settings.frame_start:
            walker.advance(dt)
        x, height = (float(v) for v in walker.pelvis)
        distance = (x - x0) * scale
        past_end = past_end or distance > route.length
        basis = solver.pose(route, distance, float(height), float(walker.pelvis_tilt),
                            walker.angles.tolist(), walker.points.tolist(), scale)
        for name, matrix in basis.items():
            pose_bone = obj.pose.bones[name]
            if solver.role[name] == "pelvis":
                keys.add(name, "location", frame, matrix.to_translation())
            prop, values, previous[name] = _rotation_values(
                pose_bone, matrix.to_quaternion().normalized(), previous.get(name))
            keys.add(name, prop, frame, values)
    keys.write(obj, settings.frame_start, settings.frame_end, obj.name + " walk")
    return Result(bones=mapping, stature=stature, scale=scale * object_scale,
                  segments=dict(walker.segments), frames=settings.frame_end -
                  settings.frame_start + 1, travel=float(walker.pelvis[0]) - x0,
                  past_curve_end=past_end)


def _walk_whole_body(fg, obj, settings, mapping, measure, origin, points, metres_per_unit):
    """walk_armature with the whole body (body.py): the armature's own legs, not a stature."""
    keys = Keys()
    try:
        walker, segments, x0 = bodies.walk_body(
            fg, obj, controller_set(fg, settings), _pace(settings), mapping, measure, origin,
            points, metres_per_unit, settings.fps, settings.frame_start, settings.frame_end, keys,
            _rotation_values)
    except bodies.BodyError as error:
        raise WalkError("armature '%s': %s" % (obj.name, error)) from None
    keys.write(obj, settings.frame_start, settings.frame_end, obj.name + " walk")
    leg = segments["thigh"] + segments["shank"] + segments["ankle_height"]
    travel = float(walker.pelvis[0]) - x0
    curve_length = paths.PolylinePath(points, measure.up).length if points else float("inf")
    return Result(bones=mapping, stature=leg / HIP_HEIGHT, scale=1.0 / metres_per_unit,
                  segments=dict(segments), frames=settings.frame_end - settings.frame_start + 1,
                  travel=travel, past_curve_end=travel / metres_per_unit > curve_length)
