# The whole body: the armature as a fuzzygait.Skeleton, walked by a fuzzygait.PathFollower (arms,
# pelvis and trunk from the set's upper body controllers, feet locked while planted) and posed by
# a fuzzygait.SkeletonPoser, each frame's local rotations keyed on the bones it maps.
#
# The body's world (Y up, Z forward, X the character's left, metres) is laid on armature space by
# a fixed frame: its origin where the walk starts (under the rest hips, or the curve's start), its
# Y along the scene's up, its Z along the way the feet point at rest. A bone's pose (basis)
# rotation is its rest rotation relative to its parent undone from the poser's local rotation.
from mathutils import Matrix, Quaternion, Vector

MIN_POINT_GAP = 0.002  # m: closer curve samples are dropped (a path refuses points within 1 mm)


class BodyError(Exception):
    """An armature or a curve the whole body cannot walk; the message says why."""


def _tree(bones, pelvis):
    """The bones of the pelvis's tree, parents before children."""
    root = bones[pelvis]
    while root.parent is not None:
        root = root.parent
    return [root] + sorted(root.children_recursive, key=lambda b: len(b.parent_recursive))


def skeleton_of(fg, armature, pelvis, metres_per_unit):
    """(fuzzygait.Skeleton of the armature's rest pose in armature units, its bones in order)."""
    order = _tree(armature.data.bones, pelvis)
    index = {bone.name: i for i, bone in enumerate(order)}
    parents, offsets, rotations = [], [], []
    for bone in order:
        if bone.parent is None:
            parents.append(-1)
            offset, rotation = bone.head_local, bone.matrix_local.to_quaternion()
        else:
            parent = bone.parent.matrix_local
            parents.append(index[bone.parent.name])
            offset = parent.inverted() @ bone.head_local
            rotation = (parent.to_3x3().inverted() @ bone.matrix_local.to_3x3()).to_quaternion()
        offsets.append(tuple(offset))
        rotations.append(tuple(rotation.normalized()))
    skeleton = fg.Skeleton([b.name for b in order], parents, offsets, rotations,
                           metres_per_unit=metres_per_unit)
    return skeleton, order


def poser_of(fg, skeleton, mapping):
    """A SkeletonPoser: its joints found by name, else the add-on's leg map given by hand."""
    try:
        return fg.SkeletonPoser(skeleton)
    except ValueError as by_name:
        given = {"hips": mapping["pelvis"]}
        for side, word in (("l", "left"), ("r", "right")):
            for role, joint in (("thigh", "UpperLeg"), ("shin", "LowerLeg"), ("foot", "Foot"),
                                ("toe", "Toes")):
                if mapping[role + "_" + side]:
                    given[word + joint] = mapping[role + "_" + side]
        try:
            return fg.SkeletonPoser(skeleton, given)
        except ValueError as by_hand:
            raise BodyError("the body's joints cannot be found (%s; by the bone map: %s)"
                            % (by_name, by_hand)) from None


class Frame:
    """The body's world on armature space: origin, axes and units."""

    def __init__(self, origin, measure, metres_per_unit):
        self.origin = origin.copy()
        axes = Matrix((-measure.lateral, measure.up, measure.forward)).transposed()  # columns
        self.axes = axes
        self.rotation = axes.to_quaternion()
        self.metres_per_unit = metres_per_unit

    def to_body(self, point):
        """An armature point as the body's (x, z) on the ground, metres."""
        p = self.axes.transposed() @ (point - self.origin) * self.metres_per_unit
        return p.x, p.z

    def to_armature(self, point):
        """A body point in armature units (the poser's root position) in armature space."""
        return self.origin + self.axes @ Vector(point)


def route_of(fg, frame, curve_points, lead_in):
    """The body's path: straight ahead, or through the curve's points; `lead_in` m of straight
    before its start, where the walker's pelvis already is when the walk begins."""
    if curve_points is None:
        return fg.Path([(lead_in, 0.0)], start=(0.0, -lead_in)) if lead_in > 0 else fg.Path()
    points = []
    for p in curve_points:
        q = Vector(frame.to_body(p))
        if not points or (q - points[-1]).length >= MIN_POINT_GAP:
            points.append(q)
    if len(points) < 2:
        raise BodyError("the curve has no length")
    if lead_in > MIN_POINT_GAP:
        points.insert(0, points[0] - (points[1] - points[0]).normalized() * lead_in)
    try:
        return fg.Path.polyline([tuple(p) for p in points], corner_radius=1.0)
    except ValueError as error:
        raise BodyError("the curve cannot be walked by the whole body: %s" % error) from None


def walk_body(fg, obj, set_, pace, mapping, measure, origin, curve_points, metres_per_unit, fps,
              first, last, keys, rotation_values):
    """Keys the bones the poser moves for frames first to last; returns (walker, skeleton's
    humanoid's segments, the walker's x at the first frame)."""
    skeleton, order = skeleton_of(fg, obj, mapping["pelvis"], metres_per_unit)
    poser = poser_of(fg, skeleton, mapping)
    try:
        walker = fg.Walker(set_, segments=poser.humanoid.segments, **pace)
    except (ValueError, TypeError) as error:
        raise BodyError("the walker cannot walk this armature: %s" % error) from None
    frame = Frame(origin, measure, metres_per_unit)
    x0 = float(walker.pelvis[0])
    follower = fg.PathFollower(poser.humanoid, route_of(fg, frame, curve_points, x0), walker)
    moved = {order[0].name} | set(poser.map.values())
    rest = [Quaternion(q) for q in skeleton.rotations]
    rest_head = order[0].head_local
    previous = {}
    for number in range(first, last + 1):
        if number > first:
            walker.advance(1.0 / fps)
        local, root = poser.pose(*follower.update())
        for i, bone in enumerate(order):
            if bone.name not in moved:
                continue
            rotation = Quaternion(local[i])
            if i == 0:  # the root's local rotation is from the body's world
                rotation = frame.rotation @ rotation
                head = frame.to_armature(root)
                keys.add(bone.name, "location", number, rest[0].inverted() @ (head - rest_head))
            basis = (rest[i].inverted() @ rotation).normalized()
            prop, values, previous[bone.name] = rotation_values(
                obj.pose.bones[bone.name], basis, previous.get(bone.name))
            keys.add(bone.name, prop, number, values)
    return walker, poser.humanoid.segments, x0
