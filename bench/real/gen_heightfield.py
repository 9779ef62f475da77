#!/usr/bin/env python3
"""gen_heightfield.py: writes bench/real/heightfield.rib: a terrain of 16 x 16 = 256 separate
`Patch "bilinear"` requests sampled from a height function (160 x 160 units, up to about 45
high), the way late-1990s DEM-to-RIB converters wrote terrain, weathered by shaders/dunes.sl
(noise and small bumps added straight up), under a shadowspot low in the sky.

    python3 bench/real/gen_heightfield.py

The file is a two-pass scene as scanline-era exporters wrote it: the patches are kept once as
an object (ObjectBegin 1 ... ObjectEnd, before the frames); frame 1 renders the light's depth
map (Display "zfile"), MakeShadow turns it into heightfield.shd, and frame 2, the image, asks for
shadows by giving the shadowspot that map's name. affray traces shadows itself: it reads and
skips frame 1 and the MakeShadow, and renders frame 2.
"""
import math
import os

from ribwrite import lookat, nums, transform_line

HERE = os.path.dirname(os.path.abspath(__file__))
N = 16            # patches a side
SIZE = 160.0      # units a side
LIGHT_FROM = (-120.0, 45.0, 170.0)
LIGHT_TO = (5.0, -5.0, 5.0)


def height(x, y):
    h = 30 * math.exp(-((x - 18) ** 2 + (y - 12) ** 2) / 700.0)
    h += 38 * math.exp(-((x + 38) ** 2 + (y - 45) ** 2) / 500.0)
    h += 16 * math.exp(-((x - 50) ** 2 + (y + 45) ** 2) / 400.0)
    h += 5 * math.sin(0.07 * x + 0.4) * math.cos(0.055 * y - 0.3)
    h += 2.5 * math.sin(0.17 * x - 0.11 * y)
    h -= 12 * math.exp(-((x + 10) ** 2 / 2500.0 + (y + 30) ** 2 / 150.0))   # a valley
    return h


def terrain_patches(indent):
    out = []
    step = SIZE / N
    for j in range(N):
        for i in range(N):
            x0, y0 = -SIZE / 2 + i * step, -SIZE / 2 + j * step
            corners = [(x0, y0), (x0 + step, y0), (x0, y0 + step), (x0 + step, y0 + step)]
            flat = [c for x, y in corners for c in (x, y, height(x, y))]
            out.append('%sPatch "bilinear" "P" [%s]' % (indent, nums(flat)))
    return out


def world(indent, shading):
    L = ["%sWorldBegin" % indent]
    i2 = indent + "\t"
    if shading:
        L += [
            '%sLightSource "ambientlight" 1 "intensity" [0.12] "lightcolor" [0.75 0.8 1]' % i2,
            '%sLightSource "shadowspot" 2 "from" [%s] "to" [%s]' % (i2, nums(LIGHT_FROM), nums(LIGHT_TO)),
            '%s\t"intensity" [52000] "lightcolor" [1 0.93 0.82] "coneangle" [0.55] "conedeltaangle" [0.1]' % i2,
            '%s\t"shadowname" ["heightfield.shd"] "samples" [16] "width" [2] "bias" [0.5]' % i2,
        ]
    L += [
        "%sAttributeBegin" % i2,
        '%s\tAttribute "identifier" "name" ["terrain"]' % i2,
    ]
    if shading:
        L += [
            "%s\tColor [0.62 0.55 0.42]" % i2,
            '%s\tSurface "plastic" "Ka" [1] "Kd" [0.75] "Ks" [0.1] "roughness" [0.3]' % i2,
            '%s\tAttribute "displacementbound" "sphere" [6] "coordinatesystem" ["shader"]' % i2,
            '%s\tDisplacement "dunes" "Km" [6] "frequency" [0.045] "Kbump" [0.8]' % i2,
        ]
    else:
        L.append('%s\tSurface "null"' % i2)
    L += [
        "%s\tObjectInstance 1" % i2,
        "%sAttributeEnd" % i2,
        "%sWorldEnd" % indent,
    ]
    return L


def main():
    L = [
        "##RenderMan RIB",
        "##Scene heightfield",
        "##Creator bench/real/gen_heightfield.py (in the style of a 1999 DEM-to-RIB converter)",
        "##CreationDate Tue Jun 22 09:41:37 1999",
        "##Frames 2",
        "version 3.03",
        'Declare "shadowname" "uniform string"',
        'Declare "Kbump" "uniform float"',
        'Option "searchpath" "shader" [".:./shaders:&"]',
        "ObjectBegin 1",
    ]
    L += terrain_patches("\t")
    L += [
        "ObjectEnd",
        "FrameBegin 1",
        '\tDisplay "heightfield.z" "zfile" "z"',
        "\tFormat 512 512 1",
        "\tPixelSamples 1 1",
        '\tProjection "perspective" "fov" [62]',
        "\tClipping 10 1000",
        "\t" + transform_line(lookat(LIGHT_FROM, LIGHT_TO)),
    ]
    L += world("\t", False)
    L += [
        "FrameEnd",
        'MakeShadow "heightfield.z" "heightfield.shd"',
        "FrameBegin 2",
        '\tDisplay "heightfield.tif" "file" "rgba"',
        "\tFormat 480 360 1",
        "\tPixelSamples 1 1",
        "\tShadingRate 1",
        '\tProjection "perspective" "fov" [34]',
        "\tClipping 1 2000",
        "\t" + transform_line(lookat((118.0, -158.0, 105.0), (-2.0, 6.0, 8.0))),
    ]
    L += world("\t", True)
    L.append("FrameEnd")
    with open(os.path.join(HERE, "heightfield.rib"), "w") as f:
        f.write("\n".join(L) + "\n")
    print("gen_heightfield.py: wrote heightfield.rib (%d bilinear patches)" % (N * N))


if __name__ == "__main__":
    main()
