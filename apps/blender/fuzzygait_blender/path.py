# Where the walk goes, in armature space: a ground point and a level heading for each distance
# travelled (armature units). Straight: from under the hips along the armature's facing. Along a
# curve: by arc length along its first spline as evaluated (Bezier or poly), from its start;
# past the end it goes straight on along the last tangent.
import bisect

from mathutils import Vector
from mathutils.geometry import interpolate_bezier

BEZIER_SAMPLES = 128  # points per Bezier segment: 0.1 mm off a 4 m quarter circle


class PathError(Exception):
    pass


class StraightPath:
    def __init__(self, start, forward):
        self.start = start.copy()
        self.forward = forward.copy()
        self.length = float("inf")

    def at(self, s):
        """(ground point, unit heading) at distance s."""
        return self.start + self.forward * s, self.forward


class PolylinePath:
    def __init__(self, points, up):
        self.points = [p.copy() for p in points]
        self.up = up
        self.cumulative = [0.0]
        for a, b in zip(self.points, self.points[1:]):
            self.cumulative.append(self.cumulative[-1] + (b - a).length)
        self.length = self.cumulative[-1]
        if len(self.points) < 2 or self.length <= 0:
            raise PathError("the curve has no length")

    def _level(self, v):
        v = v - self.up * v.dot(self.up)
        if v.length < 1e-12:
            raise PathError("the curve runs straight up or down: the walk needs level headings")
        return v.normalized()

    def at(self, s):
        i = bisect.bisect_right(self.cumulative, s) - 1
        i = min(max(i, 0), len(self.points) - 2)
        a, b = self.points[i], self.points[i + 1]
        span = self.cumulative[i + 1] - self.cumulative[i]
        t = (s - self.cumulative[i]) / span if span > 0 else 0.0
        return a.lerp(b, t) if 0 <= t <= 1 else a + (b - a) * t, self._level(b - a)


def curve_points(curve_object, depsgraph):
    """World points of the evaluated curve's first spline, in order."""
    evaluated = curve_object.evaluated_get(depsgraph)
    splines = evaluated.data.splines
    if len(splines) == 0:
        raise PathError("curve '%s' has no spline" % curve_object.name)
    spline = splines[0]
    world = evaluated.matrix_world
    if spline.type == "BEZIER":
        knots = list(spline.bezier_points)
        pairs = list(zip(knots, knots[1:]))
        if spline.use_cyclic_u and len(knots) > 1:
            pairs.append((knots[-1], knots[0]))
        points = []
        for a, b in pairs:
            segment = interpolate_bezier(a.co, a.handle_right, b.handle_left, b.co,
                                         BEZIER_SAMPLES + 1)
            points.extend(segment if not points else segment[1:])
    elif spline.type == "POLY":
        points = [p.co.xyz for p in spline.points]
        if spline.use_cyclic_u and points:
            points.append(points[0])
    else:
        raise PathError("curve '%s' is %s: the walk follows Bezier and poly splines (convert it)"
                        % (curve_object.name, spline.type))
    if len(points) < 2:
        raise PathError("curve '%s' has fewer than two points" % curve_object.name)
    return [world @ Vector(p) for p in points]
