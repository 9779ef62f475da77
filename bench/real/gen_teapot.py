#!/usr/bin/env python3
"""gen_teapot.py: writes bench/real/teapot_dented.rib and bench/real/emboss_teapot.rib (and the
emboss scene's picture, maps/utah.tif), both built on the Newell teapot of newell_teapot.py.

    python3 bench/real/gen_teapot.py

teapot_dented.rib is written the way a 1998 modeller's RIB export for BMRT looked: a header, the
camera as one Transform, BMRT's `Attribute "light" "shadows" ["on"]` before the two spotlights
that cast shadows, the floor a bilinear patch, the backdrop a bicubic patch, a vase of revolution
as 12 bicubic Bezier patches, and the teapot as its 32 bicubic Bezier patches (the degenerate
ones included), dented by shaders/dented98.sl with Km 2 and a displacement bound of 0.2 in world
space.

emboss_teapot.rib follows the emboss figure of "Advanced RenderMan" (1999, chapter 8): the same
teapot with a picture (the word UTAH) embossed on the four upper body patches, inside a large
sphere with Surface "constant" as the background, lit by two distant lights with no shadows
asked for (prman 3.x had none to ask for).
"""
import math
import os

import imagewrite
import newell_teapot
from ribwrite import lookat, nums, num, transform_line

HERE = os.path.dirname(os.path.abspath(__file__))


def teapot_patches(indent, per_patch=None):
    """The 32 Patch requests; per_patch(k) may return lines to put before patch k."""
    out = []
    names = (["rim"] * 4 + ["body"] * 8 + ["handle"] * 4 + ["spout"] * 4 + ["lid"] * 8 + ["bottom"] * 4)
    for k in range(32):
        pts = newell_teapot.patch_points(k)
        out.append("%sAttributeBegin" % indent)
        out.append('%s\tAttribute "identifier" "name" ["teapot|%s|patch%02d"]' % (indent, names[k], k + 1))
        if per_patch:
            out.extend(indent + "\t" + line for line in per_patch(k))
        flat = [c for p in pts for c in p]
        out.append('%s\tPatch "bicubic" "P" [ %s ]' % (indent, nums(flat, 12, indent + "\t\t")))
        out.append("%sAttributeEnd" % indent)
    return out


# The vase: a profile of three cubic Bezier segments (r, z), G1 where they meet, turned about z
# as four quarter arcs each (the cubic arc with handles 0.5523 of the radius long).
VASE_PROFILE = [
    [(0.9, 0.0), (1.3, 0.3), (1.6, 1.2), (1.5, 2.0)],
    [(1.5, 2.0), (1.4, 2.8), (0.6, 3.0), (0.55, 3.6)],
    [(0.55, 3.6), (0.5, 4.2), (0.75, 4.25), (0.9, 4.35)],
]
ARC = 0.5522847498


def vase_patches(indent):
    out = []
    unit = [(1, 0), (1, ARC), (ARC, 1), (0, 1)]
    for s, seg in enumerate(VASE_PROFILE):
        for q in range(4):
            c, d = math.cos(q * math.pi / 2), math.sin(q * math.pi / 2)
            arc = [(x * c - y * d, x * d + y * c) for x, y in unit]
            flat = []
            for r, z in seg:          # rows: v along the profile
                for ax, ay in arc:    # columns: u around
                    flat += [r * ax, r * ay, z]
            out.append('%sPatch "bicubic" "P" [ %s ]' % (indent, nums(flat, 12, indent + "\t")))
    return out


def header(name, creator_note):
    return [
        "##RenderMan RIB",
        "##Scene %s" % name,
        "##Creator bench/real/gen_teapot.py (%s)" % creator_note,
        "##CreationDate Thu Sep 17 21:04:11 1998",
        "##For affray bench/real",
        "version 3.03",
    ]


def teapot_dented():
    L = header("teapot_dented", "a 1998 modeller's RIB export for BMRT, rewritten")
    L += [
        'Declare "Km" "uniform float"',
        'Declare "shadows" "string"',
        'Declare "coordinatesystem" "string"',
        'Option "searchpath" "shader" [".:./shaders:&"]',
        'Option "render" "max_raylevel" [4]',
        "FrameBegin 1",
        '\tDisplay "teapot_dented.tif" "file" "rgba"',
        "\tFormat 480 360 1",
        "\tPixelSamples 1 1",
        '\tPixelFilter "box" 1 1',
        "\tShadingRate 1",
        '\tProjection "perspective" "fov" [25]',
        "\tClipping 0.1 1000",
        "\t" + transform_line(lookat((8.5, -12.5, 7.0), (-0.9, 0.6, 1.45))),
        "\tWorldBegin",
        '\t\tAttribute "identifier" "name" ["default"]',
        '\t\tLightSource "ambientlight" 1 "intensity" [0.06] "lightcolor" [1 1 1]',
        '\t\tAttribute "light" "shadows" ["on"]',
        '\t\tLightSource "spotlight" 2 "from" [7 -7 11] "to" [-0.5 0.5 1] "intensity" [210]',
        '\t\t\t"coneangle" [0.42] "conedeltaangle" [0.1] "lightcolor" [1 0.96 0.9]',
        '\t\tLightSource "spotlight" 3 "from" [-10 -6 6] "to" [-1 0.5 1.5] "intensity" [70]',
        '\t\t\t"coneangle" [0.5] "conedeltaangle" [0.15] "lightcolor" [0.75 0.8 1]',
        '\t\tAttribute "light" "shadows" ["off"]',
        "\t\tAttributeBegin",
        '\t\t\tAttribute "identifier" "name" ["floor"]',
        "\t\t\tColor [0.7 0.68 0.62]",
        '\t\t\tSurface "matte" "Ka" [1] "Kd" [0.8]',
        '\t\t\tPatch "bilinear" "P" [ -30 -30 0  30 -30 0  -30 5 0  30 5 0 ]',
        "\t\tAttributeEnd",
        "\t\tAttributeBegin",
        '\t\t\tAttribute "identifier" "name" ["backdrop"]',
        "\t\t\tColor [0.55 0.6 0.68]",
        '\t\t\tSurface "matte" "Ka" [1] "Kd" [0.8]',
        '\t\t\tBasis "bezier" 3 "bezier" 3',
    ]
    # The backdrop: floor level at y = 5, curving up into a wall at y = 8.
    xs = [-30, -10, 10, 30]
    prof = [(5, 0), (8, 0), (8, 0.5), (8, 30)]
    flat = [c for y, z in prof for x in xs for c in (x, y, z)]
    L.append('\t\t\tPatch "bicubic" "P" [ %s ]' % nums(flat, 12, "\t\t\t\t"))
    L += [
        "\t\tAttributeEnd",
        "\t\tAttributeBegin",
        '\t\t\tAttribute "identifier" "name" ["vase"]',
        "\t\t\tTranslate -5.2 2.6 0",
        "\t\t\tColor [0.35 0.5 0.6]",
        '\t\t\tSurface "plastic" "Ka" [1] "Kd" [0.6] "Ks" [0.5] "roughness" [0.05]',
        '\t\t\tBasis "bezier" 3 "bezier" 3',
    ]
    L += vase_patches("\t\t\t")
    L += [
        "\t\tAttributeEnd",
        "\t\tAttributeBegin",
        '\t\t\tAttribute "identifier" "name" ["teapot"]',
        "\t\t\tRotate 12 0 0 1",
        "\t\t\tColor [0.85 0.72 0.5]",
        '\t\t\tSurface "plastic" "Ka" [1] "Kd" [0.55] "Ks" [0.6] "roughness" [0.08]',
        '\t\t\tAttribute "displacementbound" "sphere" [0.2] "coordinatesystem" ["world"]',
        '\t\t\tDisplacement "dented98" "Km" [2]',
        '\t\t\tBasis "bezier" 3 "bezier" 3',
    ]
    L += teapot_patches("\t\t\t")
    L += ["\t\tAttributeEnd", "\tWorldEnd", "FrameEnd"]
    return L


# The emboss picture: UTAH in a 5 x 7 font, blurred.
GLYPHS = {
    "U": ["X...X", "X...X", "X...X", "X...X", "X...X", "X...X", ".XXX."],
    "T": ["XXXXX", "..X..", "..X..", "..X..", "..X..", "..X..", "..X.."],
    "A": [".XXX.", "X...X", "X...X", "XXXXX", "X...X", "X...X", "X...X"],
    "H": ["X...X", "X...X", "X...X", "XXXXX", "X...X", "X...X", "X...X"],
}


def utah_picture(path):
    w, h, cell, gap = 256, 128, 10, 10
    text = "UTAH"
    pix = [0.0] * (w * h)
    total = len(text) * 5 * cell + (len(text) - 1) * gap
    x0, y0 = (w - total) // 2, (h - 7 * cell) // 2
    for n, ch in enumerate(text):
        for gy, row in enumerate(GLYPHS[ch]):
            for gx, c in enumerate(row):
                if c != "X":
                    continue
                for yy in range(cell):
                    for xx in range(cell):
                        x = x0 + n * (5 * cell + gap) + gx * cell + xx
                        pix[(y0 + gy * cell + yy) * w + x] = 1.0
    pix = imagewrite.box_blur(pix, w, h, 2)
    imagewrite.write_tiff_gray8(path, w, h, pix)


def emboss_teapot():
    L = header("emboss_teapot", "after the emboss figure of Advanced RenderMan, chapter 8")
    L += [
        'Declare "texturename" "uniform string"',
        'Declare "Km" "uniform float"',
        'Option "searchpath" "shader" [".:./shaders:&"]',
        'MakeTexture "maps/utah.tif" "maps/utah.tex" "black" "black" "gaussian" 2 2',
        'Display "emboss_teapot.tif" "file" "rgba"',
        "Format 480 360 1",
        "PixelSamples 1 1",
        "ShadingRate 1",
        'Projection "perspective" "fov" [26]',
        transform_line(lookat((9.0, -9.5, 5.5), (0.2, 0.0, 1.4))),
        "WorldBegin",
        'LightSource "ambientlight" 1 "intensity" [0.08]',
        'LightSource "distantlight" 2 "from" [6 -8 10] "to" [0 0 0] "intensity" [0.95]',
        'LightSource "distantlight" 3 "from" [-8 6 3] "to" [0 0 0] "intensity" [0.35] "lightcolor" [0.8 0.85 1]',
        "AttributeBegin",
        '\tAttribute "identifier" "name" ["background"]',
        "\tColor [0.28 0.34 0.45]",
        '\tSurface "constant"',
        "\tSphere 60 -60 60 360",
        "AttributeEnd",
        "AttributeBegin",
        '\tAttribute "identifier" "name" ["teapot"]',
        "\tColor [0.8 0.45 0.3]",
        '\tSurface "plastic" "Ka" [1] "Kd" [0.6] "Ks" [0.45] "roughness" [0.1]',
        '\tAttribute "displacementbound" "sphere" [0.12]',
        '\tBasis "bezier" 3 "bezier" 3',
    ]

    def per_patch(k):
        if 4 <= k <= 7:   # the upper body: the word, once per quarter
            return ['Displacement "emboss" "texturename" ["maps/utah.tex"] "Km" [0.1] '
                    '"sscale" [1] "tscale" [1.25] "toffset" [0.05]']
        return ['Displacement "emboss" "texturename" [""]']

    L += teapot_patches("\t", per_patch)
    L += ["AttributeEnd", "WorldEnd"]
    return L


def main():
    os.makedirs(os.path.join(HERE, "maps"), exist_ok=True)
    with open(os.path.join(HERE, "teapot_dented.rib"), "w") as f:
        f.write("\n".join(teapot_dented()) + "\n")
    utah_picture(os.path.join(HERE, "maps", "utah.tif"))
    with open(os.path.join(HERE, "emboss_teapot.rib"), "w") as f:
        f.write("\n".join(emboss_teapot()) + "\n")
    print("gen_teapot.py: wrote teapot_dented.rib, emboss_teapot.rib and maps/utah.tif")


if __name__ == "__main__":
    main()
