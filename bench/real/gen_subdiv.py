#!/usr/bin/env python3
"""gen_subdiv.py: writes bench/real/subdiv_noise.rib: four Catmull-Clark SubdivisionMesh models,
1,688 control faces in all, each pressed in by two octaves of object-space noise
(shaders/twonoise.sl, Kd 0.1), written the way an early-2000s animation package's RenderMan
export looked (a header, every object in its own attribute block with an identifier and a
ConcatTransform, the key light a shadowspot asking for traced shadows with shadowname "raytrace",
a fill distantlight without shadows).

    python3 bench/real/gen_subdiv.py

The models (control faces; all quads, closed or with an interpolated boundary):
  ball        a cube of 8 x 8 faces a side pushed onto a sphere: 384 faces, 8 valence-3 vertices
  ring        a torus of 32 x 16 faces: 512 faces, every vertex of valence 4
  block       a cube of 6 x 6 faces a side pushed onto a rounded box (|x|^4+|y|^4+|z|^4 = 1):
              216 faces, 8 valence-3 vertices
  ground      a 24 x 24 grid over gentle hills, "interpolateboundary": 576 faces
"""
import math
import os

from ribwrite import lookat, nums, num, transform_line, cross, sub, dot, normalize

HERE = os.path.dirname(os.path.abspath(__file__))


class Mesh:
    def __init__(self):
        self.points = []
        self.index = {}
        self.faces = []

    def vertex(self, key, p):
        if key not in self.index:
            self.index[key] = len(self.points)
            self.points.append(p)
        return self.index[key]


def cube_mesh(n, place):
    """A cube of n x n quads a side; place(x, y, z) maps the lattice point in [-1, 1]^3 to
    the surface. Faces run counterclockwise seen from outside (right-handed cross product out)."""
    m = Mesh()

    def lattice(a, s, i, j):
        c = [0, 0, 0]
        b, d = (a + 1) % 3, (a + 2) % 3
        c[a] = n if s > 0 else 0
        c[b], c[d] = i, j
        key = tuple(c)
        return m.vertex(key, place(*[2.0 * k / n - 1 for k in key]))

    for a in range(3):
        for s in (1, -1):
            for i in range(n):
                for j in range(n):
                    quad = [lattice(a, s, i, j), lattice(a, s, i + 1, j),
                            lattice(a, s, i + 1, j + 1), lattice(a, s, i, j + 1)]
                    m.faces.append(quad if s > 0 else quad[::-1])
    return m


def sphere_place(x, y, z):
    r = math.sqrt(x * x + y * y + z * z)
    return (x / r, y / r, z / r)


def rounded_box_place(x, y, z):
    # Push the cube's lattice point along its direction onto |x|^4 + |y|^4 + |z|^4 = 1,
    # then stretch the box a little.
    r = (x ** 4 + y ** 4 + z ** 4) ** 0.25
    return (1.2 * x / r, 0.8 * y / r, 0.7 * z / r)


def torus_mesh(nu, nv, R, r):
    m = Mesh()
    for i in range(nu):
        for j in range(nv):
            a, b = 2 * math.pi * i / nu, 2 * math.pi * j / nv
            m.vertex((i, j), ((R + r * math.cos(b)) * math.cos(a), (R + r * math.cos(b)) * math.sin(a),
                              r * math.sin(b)))
    for i in range(nu):
        for j in range(nv):
            m.faces.append([m.index[(i, j)], m.index[((i + 1) % nu, j)],
                            m.index[((i + 1) % nu, (j + 1) % nv)], m.index[(i, (j + 1) % nv)]])
    # Orient outwards: the first face's normal against the direction away from the tube's core.
    p = [m.points[k] for k in m.faces[0]]
    n = cross(sub(p[1], p[0]), sub(p[2], p[0]))
    c = p[0]
    core = (R * c[0] / math.hypot(c[0], c[1]), R * c[1] / math.hypot(c[0], c[1]), 0)
    if dot(n, sub(c, core)) < 0:
        m.faces = [f[::-1] for f in m.faces]
    return m


def ground_z(x, y):
    return 0.35 * math.sin(0.3 * x + 0.3) * math.cos(0.25 * y - 0.2) + 0.1 * math.sin(0.5 * x + 0.4 * y) - 0.2


def ground_mesh(n, size):
    m = Mesh()
    for i in range(n + 1):
        for j in range(n + 1):
            x, y = size * (i / n - 0.5), size * (j / n - 0.5)
            m.vertex((i, j), (x, y, ground_z(x, y)))
    for i in range(n):
        for j in range(n):
            m.faces.append([m.index[(i, j)], m.index[(i + 1, j)], m.index[(i + 1, j + 1)], m.index[(i, j + 1)]])
    return m


def check_closed_oriented(m, closed):
    edges = {}
    for f in m.faces:
        for k in range(len(f)):
            e = (f[k], f[(k + 1) % len(f)])
            assert e not in edges, "edge used twice in one direction: faces not consistently oriented"
            edges[e] = True
    if closed:
        for a, b in edges:
            assert (b, a) in edges, "open edge in a closed mesh"


def mesh_request(m, indent, tags=None):
    out = ['%sSubdivisionMesh "catmull-clark" [%s]' % (indent, " ".join("4" for _ in m.faces))]
    out.append("%s\t[%s]" % (indent, nums([k for f in m.faces for k in f], 32, indent + "\t ")))
    if tags:
        out.append("%s\t%s" % (indent, tags))
    out.append('%s\t"P" [%s]' % (indent, nums([c for p in m.points for c in p], 24, indent + "\t ")))
    return out


def concat(tx, ty, tz, rz=0.0, rx=0.0, s=1.0):
    """A ConcatTransform as exporters write it: scale, then rotate about x, then about z, then
    translate (row-vector matrices, RenderMan's layout)."""
    cz, sz = math.cos(math.radians(rz)), math.sin(math.radians(rz))
    cx, sx = math.cos(math.radians(rx)), math.sin(math.radians(rx))
    # rows of R = Rx * Rz (row vectors: p * Rx then * Rz)
    rx_m = [[1, 0, 0], [0, cx, sx], [0, -sx, cx]]
    rz_m = [[cz, sz, 0], [-sz, cz, 0], [0, 0, 1]]
    r = [[sum(rx_m[i][k] * rz_m[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    m = [s * r[0][0], s * r[0][1], s * r[0][2], 0,
         s * r[1][0], s * r[1][1], s * r[1][2], 0,
         s * r[2][0], s * r[2][1], s * r[2][2], 0,
         tx, ty, tz, 1]
    return "ConcatTransform [ " + " ".join(num(v) for v in m) + " ]"


def main():
    ball = cube_mesh(8, sphere_place)
    ring = torus_mesh(32, 16, 1.0, 0.36)
    block = cube_mesh(6, rounded_box_place)
    ground = ground_mesh(24, 30.0)
    for m, closed in ((ball, True), (ring, True), (block, True), (ground, False)):
        check_closed_oriented(m, closed)
    total = sum(len(m.faces) for m in (ball, ring, block, ground))

    L = [
        "##RenderMan RIB-Structure 1.0",
        "##Scene subdiv_noise",
        "##Creator bench/real/gen_subdiv.py (in the style of a 2002 animation package's RenderMan export)",
        "##CreationDate Mon Mar 11 14:22:05 2002",
        "##Frames 1",
        "version 3.04",
        'Declare "shadowname" "uniform string"',
        'Declare "Kd" "uniform float"',
        'Option "searchpath" "shader" ["@:./shaders"]',
        'Option "limits" "bucketsize" [16 16]',
        'Option "limits" "gridsize" [256]',
        "FrameBegin 1",
        "\tIdentity",
        '\tDisplay "subdiv_noise.0001.tif" "tiff" "rgba"',
        "\tFormat 480 360 1",
        "\tPixelSamples 1 1",
        '\tPixelFilter "gaussian" 2 2',
        "\tShadingRate 1",
        '\tHider "hidden" "jitter" [0]',
        "\tClipping 0.1 200",
        '\tProjection "perspective" "fov" [33]',
        "\tScreenWindow -1.33333 1.33333 -1 1",
        "\t" + transform_line(lookat((4.6, -8.0, 7.6), (0.3, 0.6, 0.2))),
        "\tWorldBegin",
        '\t\tAttribute "identifier" "name" ["perspShape"]',
        "\t\tTransformBegin",
        '\t\t\tLightSource "ambientlight" 1 "intensity" [0.05]',
        "\t\tTransformEnd",
        "\t\tTransformBegin",
        '\t\t\tAttribute "identifier" "name" ["keyLightShape"]',
        '\t\t\tLightSource "shadowspot" 2 "intensity" [130] "lightcolor" [1 0.97 0.92]',
        '\t\t\t\t"from" [-4 -6 9] "to" [0 0.3 0.5] "coneangle" [0.6] "conedeltaangle" [0.12]',
        '\t\t\t\t"shadowname" ["raytrace"] "samples" [16] "width" [1]',
        "\t\tTransformEnd",
        "\t\tTransformBegin",
        '\t\t\tAttribute "identifier" "name" ["fillLightShape"]',
        '\t\t\tLightSource "distantlight" 3 "intensity" [0.3] "lightcolor" [0.7 0.8 1]',
        '\t\t\t\t"from" [6 -2 3] "to" [0 0 0]',
        "\t\tTransformEnd",
        '\t\tAttribute "visibility" "transmission" ["opaque"]',
    ]
    objects = [
        ("groundShape", ground, concat(0, 0, 0), (0.55, 0.5, 0.42), '["interpolateboundary"] [0 0] [] []'),
        ("ballShape", ball, concat(-2.1, 0.9, ground_z(-2.1, 0.9) + 0.98, 20, 10), (0.75, 0.35, 0.25), None),
        ("ringShape", ring, concat(0.9, -1.3, ground_z(0.9, -1.3) + 1.15, -35, 62), (0.35, 0.55, 0.7), None),
        ("blockShape", block, concat(2.6, 1.6, ground_z(2.6, 1.6) + 0.66, 28), (0.6, 0.65, 0.4), None),
    ]
    for name, mesh, xform, color, tags in objects:
        L += [
            "\t\tAttributeBegin",
            '\t\t\tAttribute "identifier" "name" ["%s"]' % name,
            "\t\t\t" + xform,
            "\t\t\tColor [%s]" % nums(color),
            '\t\t\tSurface "plastic" "Ka" [1] "Kd" [0.7] "Ks" [0.35] "roughness" [0.12]',
            '\t\t\tAttribute "displacementbound" "sphere" [0.15] "coordinatesystem" ["shader"]',
            '\t\t\tDisplacement "twonoise" "Kd" [0.1]',
        ]
        L += mesh_request(mesh, "\t\t\t", tags)
        L.append("\t\tAttributeEnd")
    L += ["\tWorldEnd", "FrameEnd"]
    with open(os.path.join(HERE, "subdiv_noise.rib"), "w") as f:
        f.write("\n".join(L) + "\n")
    print("gen_subdiv.py: wrote subdiv_noise.rib (%d faces: %s)" % (
        total, ", ".join("%s %d" % (n, len(m.faces)) for n, m, *_ in objects)))


if __name__ == "__main__":
    main()
