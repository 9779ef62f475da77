#!/usr/bin/env python3
"""gen_nurbs.py: writes bench/real/nurbs_textured.rib and its 89 pictures maps/hydrant_NNN.tif.

    python3 bench/real/gen_nurbs.py

The scene is written the way an IGES-to-RIB translator of around 2001 wrote a CAD part: a
cast-iron fire hydrant in millimetres (about 790 units tall and 500 across with its nozzles) on
a ground slab, every IGES surface (entity 128, a rational B-spline surface) its own cubic
NuPatch in its own attribute block, named after the entity, with its own instance of a
map-driven displacement (shaders/paneldisp.sl) and its own map, made from a picture by a
MakeTexture request at the top of the file; one distantlight, Surface "matte".

The surfaces (89 NuPatches, order 4 x 4, knots 0..1):
  * the body: a profile of 12 cubic segments turned about z, each in 4 quarter turns (48);
    the quarter circle is the rational quadratic arc raised to degree 3 (weights 1, 0.8047,
    0.8047, 1), as CAD systems export cylinders and cones as cubics; the barrel has two knot
    spans along its height; the operating nut's top closes on the axis, so its patches have a
    control-point row collapsed to a point;
  * two hose nozzles (4 segments each, turned about the y axis, both ways: 32) and the pumper
    nozzle (2 segments, about -x: 8), their caps closing on their axes as well;
  * the ground slab, one flat cubic NuPatch (1).
Each map is 128 x 128, 8 bits: one of five patterns (cast roughness, raised ribs, bolt heads,
hammer dents, flutes) with its own seed, faded to 0 at the border so neighbouring patches meet
without cracks.
"""
import math
import os

import imagewrite
from ribwrite import Lcg, lookat, nums, transform_line

HERE = os.path.dirname(os.path.abspath(__file__))
MAP_SIZE = 128

# The quarter circle as a rational cubic: the quadratic arc (1,0) (1,1) (0,1), weights 1, r, 1
# (r = sqrt(2)/2), raised to degree 3.
_R = math.sqrt(0.5)                  # the middle weight of the quadratic arc
_W = (1 + 2 * _R) / 3                 # the inner weights of the cubic: (1 + 2 r) / 3
_K = 2 * _R / 3 / _W                  # the inner points' offset: 2 - sqrt(2) = 0.5858
ARC = [((1.0, 0.0), 1.0), ((1.0, _K), _W), ((_K, 1.0), _W), ((0.0, 1.0), 1.0)]

# The body's profile, (r, z) points of cubic Bezier segments; the barrel is a 2-span cubic
# B-spline (5 points, knots 0 0 0 0 0.5 1 1 1 1).
BODY = [
    ("flange side", [(155, 0), (155, 12), (155, 24), (155, 35)]),
    ("flange bevel", [(155, 35), (150, 42), (130, 45), (112, 48)]),
    ("barrel fillet", [(112, 48), (100, 50), (96, 60), (96, 75)]),
    ("barrel", [(96, 75), (95, 180), (99, 300), (96, 430), (100, 520)]),
    ("upper flange under", [(100, 520), (115, 522), (130, 522), (138, 526)]),
    ("upper flange side", [(138, 526), (142, 530), (142, 545), (138, 550)]),
    ("bonnet skirt", [(138, 550), (125, 555), (110, 556), (108, 562)]),
    ("dome lower", [(108, 562), (106, 590), (100, 615), (88, 632)]),
    ("dome upper", [(88, 632), (76, 649), (62, 658), (50, 662)]),
    ("nut collar", [(50, 662), (38, 666), (31, 668), (30, 672)]),
    ("nut side", [(30, 672), (31, 690), (31, 705), (30, 720)]),
    ("nut top", [(30, 720), (22, 724), (10, 725), (0, 725)]),
]
# Nozzles: (r, d) with d the distance along the nozzle's axis from the body's axis.
HOSE = [
    ("hose pipe", [(50, 70), (50, 100), (50, 125), (50, 140)]),
    ("hose cap flange", [(50, 140), (60, 141), (62, 150), (60, 158)]),
    ("hose cap", [(60, 158), (55, 160), (52, 175), (50, 185)]),
    ("hose cap face", [(50, 185), (35, 190), (15, 190), (0, 190)]),
]
PUMPER = [
    ("pumper pipe", [(72, 60), (72, 100), (72, 140), (72, 160)]),
    ("pumper cap", [(72, 160), (80, 170), (60, 182), (0, 184)]),
]


def knots(n):
    return [0, 0, 0, 0, 1, 1, 1, 1] if n == 4 else [0, 0, 0, 0, 0.5, 1, 1, 1, 1]


def revolved(profile, centre, axis, e1, e2, quarter):
    """Pw of one quarter turn of a profile about centre + d * axis: u around (4 points), v along
    the profile; e1 x e2 = axis, so dPdu x dPdv points out of the surface."""
    a0 = quarter * math.pi / 2
    c, s = math.cos(a0), math.sin(a0)
    pw = []
    for r, d in profile:
        for (x, y), w in ARC:
            xr, yr = x * c - y * s, x * s + y * c
            p = [centre[k] + d * axis[k] + r * (xr * e1[k] + yr * e2[k]) for k in range(3)]
            pw += [p[0] * w, p[1] * w, p[2] * w, w]
    return pw


# --- the pictures -------------------------------------------------------------------------

def value_noise(rng_seed, freq):
    lat = {}

    def at(i, j):
        key = (i, j)
        if key not in lat:
            h = (i * 73856093 ^ j * 19349663 ^ rng_seed * 83492791) & 0xFFFFFFFF
            lat[key] = Lcg(h).next()
        return lat[key]

    def f(x, y):
        x, y = x * freq, y * freq
        i, j = int(math.floor(x)), int(math.floor(y))
        fx, fy = x - i, y - j
        sx, sy = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy)
        a = at(i, j) + (at(i + 1, j) - at(i, j)) * sx
        b = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * sx
        return a + (b - a) * sy
    return f


def smoothstep(e0, e1, x):
    t = min(1.0, max(0.0, (x - e0) / (e1 - e0)))
    return t * t * (3 - 2 * t)


def picture(kind, seed):
    n = MAP_SIZE
    rng = Lcg(seed)
    pix = []
    octaves = [value_noise(seed * 7 + k, 4 * 2 ** k) for k in range(4)]
    centres = [(0.1 + 0.8 * rng.next(), 0.1 + 0.8 * rng.next()) for _ in range(14)]
    ribs = 3 + int(rng.next() * 5)
    bolts = 3 + int(rng.next() * 4)
    for y in range(n):
        for x in range(n):
            s, t = (x + 0.5) / n, (y + 0.5) / n
            rough = sum(o(s, t) * 0.5 ** k for k, o in enumerate(octaves)) / 1.875
            if kind == 0:      # cast roughness
                h = rough
            elif kind == 1:    # raised ribs across t
                h = 0.75 * smoothstep(0.55, 0.8, 0.5 + 0.5 * math.cos(2 * math.pi * t * ribs)) + 0.25 * rough
            elif kind == 2:    # bolt heads on a ring
                fs, ft = (s * bolts) % 1.0 - 0.5, t - 0.5
                d = math.hypot(fs / bolts * 2.2, ft)
                h = 0.8 * (1 - smoothstep(0.06, 0.1, d)) + 0.2 * rough
            elif kind == 3:    # hammer dents: distance to scattered centres
                d = min(math.hypot(s - cx, t - cy) for cx, cy in centres)
                h = 0.7 * smoothstep(0.0, 0.14, d) + 0.3 * rough
            else:              # flutes along t
                h = 0.6 * (0.5 + 0.5 * math.cos(2 * math.pi * s * (ribs + 3))) + 0.4 * rough
            edge = smoothstep(0.0, 0.1, s) * smoothstep(0.0, 0.1, 1 - s) * smoothstep(0.0, 0.1, t) * \
                smoothstep(0.0, 0.1, 1 - t)
            pix.append(h * edge)
    return pix


# --- the scene ---------------------------------------------------------------------------

def main():
    os.makedirs(os.path.join(HERE, "maps"), exist_ok=True)
    surfaces = []   # (name, colour, Km, bias, NuPatch request text)

    def nupatch(pw, nv):
        return ('NuPatch 4 4 [%s] 0 1 %d 4 [%s] 0 1\n\t\t"Pw" [%s]' %
                (nums(knots(4)), nv, nums(knots(nv)), nums(pw, 16, "\t\t\t")))

    red, grey, cap = (0.62, 0.1, 0.07), (0.5, 0.5, 0.48), (0.72, 0.6, 0.2)
    for name, prof in BODY:
        for q in range(4):
            pw = revolved(prof, (0, 0, 0), (0, 0, 1), (1, 0, 0), (0, 1, 0), q)
            surfaces.append((name, red if "nut" not in name else cap, 9, 0.3, nupatch(pw, len(prof))))
    nozzles = [((0, 0, 390), (0, 1, 0), (0, 0, 1), (1, 0, 0), HOSE),
               ((0, 0, 390), (0, -1, 0), (1, 0, 0), (0, 0, 1), HOSE),
               ((0, 0, 330), (-1, 0, 0), (0, 0, 1), (0, 1, 0), PUMPER)]
    for centre, axis, e1, e2, segs in nozzles:
        for name, prof in segs:
            for q in range(4):
                pw = revolved(prof, centre, axis, e1, e2, q)
                surfaces.append((name, red if "pipe" in name else cap, 7, 0.3, nupatch(pw, len(prof))))
    ground = []
    for j in range(4):
        for i in range(4):
            ground += [-6000 + 4000 * i, -6000 + 4000 * j, 0, 1]
    surfaces.append(("ground slab", grey, 14, 0.0, nupatch(ground, 4)))
    assert len(surfaces) == 89

    L = [
        "##RenderMan RIB",
        "##Scene nurbs_textured",
        "##Creator bench/real/gen_nurbs.py (in the style of an IGES-to-RIB translator's output, 2001)",
        "##CreationDate Fri Nov 30 16:05:52 2001",
        "##Source hydrant.igs: 89 entities of type 128 (rational B-spline surface), units MM",
        "version 3.03",
        'Declare "mapname" "uniform string"',
        'Declare "bias" "uniform float"',
        'Option "searchpath" "shader" ["./shaders:&"]',
        'Option "searchpath" "texture" ["./maps:&"]',
    ]
    for k in range(len(surfaces)):
        L.append('MakeTexture "maps/hydrant_%03d.tif" "maps/hydrant_%03d.tx" "clamp" "clamp" "gaussian" 2 2' % (k, k))
    L += [
        'Display "nurbs_textured.tif" "file" "rgb"',
        "Format 480 360 1",
        "PixelSamples 1 1",
        "ShadingRate 1",
        'Projection "perspective" "fov" [24]',
        "Clipping 10 20000",
        transform_line(lookat((1550.0, -1350.0, 980.0), (-20.0, 10.0, 330.0))),
        "WorldBegin",
        'LightSource "ambientlight" 1 "intensity" [0.15]',
        'LightSource "distantlight" 2 "intensity" [1.0] "from" [1000 -400 1400] "to" [0 0 0]',
        'Surface "matte"',
    ]
    for k, (name, colour, km, bias, request) in enumerate(surfaces):
        L += [
            "AttributeBegin",
            '\tAttribute "identifier" "name" ["IGES_128_%04d %s"]' % (2 * k + 1, name),
            "\tColor [%s]" % nums(colour),
            '\tDisplacement "paneldisp" "mapname" ["hydrant_%03d.tx"] "Km" [%s] "bias" [%s]' % (k, km, bias),
            "\t" + request,
            "AttributeEnd",
        ]
    L.append("WorldEnd")
    with open(os.path.join(HERE, "nurbs_textured.rib"), "w") as f:
        f.write("\n".join(L) + "\n")
    for k in range(len(surfaces)):
        kind = 0 if k == 88 else (k * 7 + k // 4) % 5
        imagewrite.write_tiff_gray8(os.path.join(HERE, "maps", "hydrant_%03d.tif" % k), MAP_SIZE, MAP_SIZE,
                                    picture(kind, 1000 + k))
    print("gen_nurbs.py: wrote nurbs_textured.rib (%d NuPatches) and %d pictures in maps/" %
          (len(surfaces), len(surfaces)))


if __name__ == "__main__":
    main()
