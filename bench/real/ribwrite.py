"""ribwrite.py: small helpers the bench/real generators share (Python 3 standard library only).

Numbers are written the way exporters of the time wrote them (up to 6 significant digits,
no exponent for ordinary values), cameras as a full `Transform` matrix.
"""
import math


def num(x):
    """One number as a RIB exporter writes it: %g with 6 significant digits, -0 as 0."""
    if abs(x) < 5e-7:
        return "0"
    s = "%.6g" % x
    return s


def nums(values, per_line=0, indent=""):
    """Numbers separated by spaces; with per_line, broken into lines of that many."""
    items = [num(v) for v in values]
    if not per_line:
        return " ".join(items)
    lines = [" ".join(items[i:i + per_line]) for i in range(0, len(items), per_line)]
    return ("\n" + indent).join(lines)


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def lookat(eye, target, up=(0, 0, 1)):
    """The world-to-camera matrix (RenderMan's row-vector layout, 16 numbers) of a camera at eye
    looking at target with up roughly `up`. It is a rotation and a translation (determinant +1),
    so the world keeps the camera's left-handed orientation, as in RI scenes placed by Rotate and
    Translate."""
    f = normalize(sub(target, eye))
    r = normalize(cross(up, f))
    u = cross(f, r)
    return [r[0], u[0], f[0], 0,
            r[1], u[1], f[1], 0,
            r[2], u[2], f[2], 0,
            -dot(eye, r), -dot(eye, u), -dot(eye, f), 1]


def transform_line(m):
    return "Transform [ " + " ".join(num(v) for v in m) + " ]"


class Lcg:
    """A tiny deterministic generator (the same numbers on every Python), for the scripts' noise."""

    def __init__(self, seed):
        self.state = (seed * 2654435761 + 12345) & 0xFFFFFFFF

    def next(self):
        self.state = (1103515245 * self.state + 12345) & 0x7FFFFFFF
        return self.state / 0x7FFFFFFF
