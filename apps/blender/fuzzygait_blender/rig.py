# Which pose bones of an armature are the walker's pelvis and legs, and the armature's leg
# geometry at rest, measured in the armature's own space (its units, its axes).
#
# Three naming schemes are recognised: the skeleton of `fuzzygait walk`'s BVH as Blender's BVH
# importer builds it (Hips, LeftUpLeg, LeftLeg, LeftFoot, LeftToeBase, Spine), Mixamo's (the same
# names behind a "mixamorig:" namespace) and Rigify's meta-rig (spine, thigh.L, shin.L, foot.L,
# toe.L, spine.001). Names are compared without a namespace ("xyz:") and without case.
import math
from dataclasses import dataclass

from mathutils import Vector

# The roles of the bone map: (key, words for messages, required).
ROLES = (
    ("pelvis", "pelvis", True),
    ("spine", "spine", False),
    ("thigh_l", "left thigh", True),
    ("shin_l", "left shin", True),
    ("foot_l", "left foot", True),
    ("toe_l", "left toe", False),
    ("thigh_r", "right thigh", True),
    ("shin_r", "right shin", True),
    ("foot_r", "right foot", True),
    ("toe_r", "right toe", False),
)
ROLE_WORDS = {key: words for key, words, _ in ROLES}

# Candidate names per role, normalised (no namespace, lower case); the first present wins.
_LEFT = {
    "thigh": ("leftupleg", "thigh.l", "thigh_fk.l", "thigh_l", "upperleg.l", "leftthigh"),
    "shin": ("leftleg", "shin.l", "shin_fk.l", "shin_l", "calf.l", "calf_l", "lowerleg.l",
             "leftshin"),
    "foot": ("leftfoot", "foot.l", "foot_fk.l", "foot_l"),
    "toe": ("lefttoebase", "toe.l", "toe_l", "lefttoe", "toes.l", "ball_l"),
}


def _right(name):
    if name.startswith("left"):
        return "right" + name[4:]
    return name[:-1] + "r"  # thigh.l -> thigh.r, thigh_l -> thigh_r


CANDIDATES = {
    "pelvis": ("hips", "pelvis", "spine"),
    "spine": ("spine", "spine.001", "spine1"),
}
for _part, _names in _LEFT.items():
    CANDIDATES[_part + "_l"] = _names
    CANDIDATES[_part + "_r"] = tuple(_right(n) for n in _names)


class RigError(Exception):
    """A bone map or an armature the walk cannot use; the message says what is missing."""


def normalise(name):
    return name.rsplit(":", 1)[-1].lower()


def auto_map(bones):
    """{role: bone name or ""} for the bones (an armature's data.bones) by their names."""
    by_name = {}
    for bone in bones:
        by_name.setdefault(normalise(bone.name), bone.name)
    mapping = {}
    for key, _, _ in ROLES:
        found = ""
        for candidate in CANDIDATES[key]:
            name = by_name.get(candidate, "")
            if name and name != mapping.get("pelvis"):
                found = name
                break
        mapping[key] = found
    return mapping


def resolve_map(bones, given):
    """The bone map: given names (role -> name, "" for automatic) completed automatically.
    Raises RigError naming each missing or unknown bone and each chain that does not hold."""
    automatic = auto_map(bones)
    mapping = {}
    problems = []
    for key, words, required in ROLES:
        name = given.get(key, "") or ""
        if name and name not in bones:
            problems.append("%s bone '%s' is not in the armature" % (words, name))
            continue
        name = name or automatic[key]
        if not name and required:
            tried = ", ".join(CANDIDATES[key])
            problems.append("no %s bone (tried %s)" % (words, tried))
        mapping[key] = name
    if problems:
        raise RigError("; ".join(problems) + ": set the bone map")
    for side in ("l", "r"):
        chain = [mapping["pelvis"]] + [mapping[p + "_" + side] for p in ("thigh", "shin", "foot")]
        if mapping["toe_" + side]:
            chain.append(mapping["toe_" + side])
        for parent, child in zip(chain, chain[1:]):
            if bones[parent] not in bones[child].parent_recursive:
                problems.append("'%s' is not a descendant of '%s'" % (child, parent))
    spine = mapping["spine"]
    if spine and bones[mapping["pelvis"]] not in bones[spine].parent_recursive:
        problems.append("spine '%s' is not a descendant of the pelvis '%s'"
                        % (mapping["spine"], mapping["pelvis"]))
    if problems:
        raise RigError("; ".join(problems) + ": set the bone map")
    return mapping


@dataclass
class Measure:
    """The armature at rest in armature space: its axes, where the hips and the ground are, and
    the legs' sagittal lengths (armature units, each the mean of both legs)."""
    up: Vector         # world +Z, in armature space (unit)
    forward: Vector    # where the feet point, level (unit)
    lateral: Vector    # forward x up (the character's right): rotations about it
    hip: Vector        # midpoint of the thigh heads
    ground: float      # height (along up) of the lowest point of the feet
    thigh: float       # thigh head to shin head, in the sagittal plane
    shank: float       # shin head to foot head
    ankle_height: float
    ball: float        # foot head to toe head (or the foot's tail), forward
    toe: float         # the toe bone, 0 without one
    rest_angle: dict   # bone name -> rest inclination (thigh, shin), radians

    @property
    def leg_length(self):
        return self.thigh + self.shank + self.ankle_height


def sagittal(v, forward, up):
    """(forward, up) components of v."""
    return v.dot(forward), v.dot(up)


def inclination(v, forward, up):
    """v's angle from the downward vertical, forward +, in the sagittal plane."""
    f, u = sagittal(v, forward, up)
    return math.atan2(f, -u)


def measure(armature_object, mapping):
    """Measure the armature's legs at rest. Raises RigError for degenerate legs."""
    bones = armature_object.data.bones
    up = (armature_object.matrix_world.to_3x3().inverted_safe() @ Vector((0, 0, 1)))
    if up.length < 1e-12:
        raise RigError("armature '%s' has a degenerate transform" % armature_object.name)
    up.normalize()

    feet = []
    for side in ("l", "r"):
        foot = bones[mapping["foot_" + side]]
        toe = bones[mapping["toe_" + side]] if mapping["toe_" + side] else None
        tip = toe.tail_local if toe else foot.tail_local
        feet.append(tip - foot.head_local)
    forward = sum(feet, Vector((0, 0, 0)))
    forward -= up * forward.dot(up)
    if forward.length < 1e-9:
        raise RigError("the feet of '%s' do not point forward at rest" % armature_object.name)
    forward.normalize()
    lateral = forward.cross(up)

    def points(bone):
        yield bone.head_local
        yield bone.tail_local
        for child in bone.children_recursive:
            yield child.head_local
            yield child.tail_local

    ground = min(p.dot(up) for side in ("l", "r") for p in points(bones[mapping["foot_" + side]]))
    hip = (bones[mapping["thigh_l"]].head_local + bones[mapping["thigh_r"]].head_local) / 2

    sums = {"thigh": 0.0, "shank": 0.0, "ankle_height": 0.0, "ball": 0.0, "toe": 0.0}
    rest_angle = {}
    for side in ("l", "r"):
        thigh, shin, foot = (bones[mapping[p + "_" + side]] for p in ("thigh", "shin", "foot"))
        toe = bones[mapping["toe_" + side]] if mapping["toe_" + side] else None
        for bone, end in ((thigh, shin), (shin, foot)):
            v = end.head_local - bone.head_local
            length = math.hypot(*sagittal(v, forward, up))
            if length < 1e-9:
                raise RigError("bone '%s' has no length in the walking plane" % bone.name)
            sums["thigh" if bone is thigh else "shank"] += length / 2
            rest_angle[bone.name] = inclination(v, forward, up)
        sums["ankle_height"] += (foot.head_local.dot(up) - ground) / 2
        ball_end = toe.head_local if toe else foot.tail_local
        sums["ball"] += (ball_end - foot.head_local).dot(forward) / 2
        if toe:
            sums["toe"] += math.hypot(*sagittal(toe.tail_local - toe.head_local, forward, up)) / 2
    if sums["ankle_height"] <= 0 or sums["ball"] <= 0:
        raise RigError("the feet of '%s' are not below the ankles and forward of them at rest"
                       % armature_object.name)
    return Measure(up=up, forward=forward, lateral=lateral, hip=hip, ground=ground,
                   rest_angle=rest_angle, **sums)
