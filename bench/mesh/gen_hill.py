#!/usr/bin/env python3
"""gen_hill.py: writes a displaced hill of N x N quads as one PointsPolygons with vertex normals,
the production-size mesh benchmark of issue 32 (a grid bent into a hill, noise displacement).

    python3 bench/mesh/gen_hill.py N OUT.rib [--xres 640 --yres 480] [--subdivision]

The grid spans 20 x 20 units; the hill is a Gaussian bump 4 units high; normals are the
analytic surface normals at the vertices. With --subdivision the same grid is a Catmull-Clark
SubdivisionMesh (no normals: the limit surface's). The displacement is shaders/dented.sl (two octaves,
Km 0.3, frequency 1.5), under one shadowed distant light.
"""
import argparse
import math
import os
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("n", type=int)
    ap.add_argument("out")
    ap.add_argument("--xres", type=int, default=640)
    ap.add_argument("--yres", type=int, default=480)
    ap.add_argument("--subdivision", action="store_true")
    a = ap.parse_args()
    n = a.n
    size = 20.0

    def height(x, y):
        return 4.0 * math.exp(-(x * x + y * y) / 40.0)

    def normal(x, y):
        h = height(x, y)
        dx, dy = -2 * x / 40.0 * h, -2 * y / 40.0 * h
        l = math.sqrt(dx * dx + dy * dy + 1)
        return (-dx / l, -dy / l, 1 / l)

    with open(a.out, "w") as f:
        w = f.write
        w("##RenderMan RIB\n")
        w('Display "hill.exr" "file" "rgba"\n')
        w("Format %d %d 1\nPixelSamples 1 1\nProjection \"perspective\" \"fov\" [40]\n" % (a.xres, a.yres))
        w("Translate 0 -1 24\nRotate -120 1 0 0\n")
        w("Rotate 20 0 0 1\n")
        w("WorldBegin\n")
        w('LightSource "ambientlight" 1 "intensity" [0.1]\n')
        w('LightSource "distantlight" 2 "from" [-1 -1 2] "to" [0 0 0] "intensity" [1]\n')
        w('Attribute "displacementbound" "sphere" [0.2]\n')
        w('Displacement "dented" "Km" [0.3] "frequency" [1.5] "octaves" [2]\n')
        w('Surface "matte"\n')
        nv = (n + 1) * (n + 1)
        if a.subdivision:
            w('SubdivisionMesh "catmull-clark" [')
        else:
            w("PointsPolygons [")
        w(" ".join("4" for _ in range(n * n)))
        w("]\n[")
        idx = []
        for j in range(n):
            for i in range(n):
                v0 = j * (n + 1) + i
                idx.append("%d %d %d %d" % (v0, v0 + 1, v0 + n + 2, v0 + n + 1))
        w(" ".join(idx))
        w("]\n")
        if a.subdivision:
            w('["interpolateboundary"] [0 0] [] []\n')
        w("\"P\" [")
        pts, nrm = [], []
        for j in range(n + 1):
            for i in range(n + 1):
                x, y = -size / 2 + size * i / n, -size / 2 + size * j / n
                pts.append("%.6g %.6g %.6g" % (x, y, height(x, y)))
                nrm.append("%.6g %.6g %.6g" % normal(x, y))
        w(" ".join(pts))
        if not a.subdivision:
            w("]\n\"N\" [")
            w(" ".join(nrm))
        w("]\nWorldEnd\n")
    print("wrote %s: %d quads, %d vertices" % (a.out, n * n, nv), file=sys.stderr)


if __name__ == "__main__":
    main()
