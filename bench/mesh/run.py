#!/usr/bin/env python3
"""bench/mesh/run.py: production-size meshes (issue 32): renders displaced hills of N x N quads
(bench/mesh/gen_hill.py: one PointsPolygons with vertex normals, or with --subdivision a
Catmull-Clark SubdivisionMesh) and prints one Markdown table.

    python3 bench/mesh/run.py [--affray build/tools/affray] [--sizes 100,316,1000] [--subdivision 316]
                              [--threads 2] [--json OUT.json]

Each scene is written to a temporary directory (the 1000 x 1000 one is 77 MB), rendered once at
640x480 and 1 sample with `affray render SCENE -o TMP.exr --stats --quiet --threads N`, and
deleted. The table gives per scene: faces, the seconds reading the RIB file (read_seconds), preparing
the scene (prepare_seconds: shaders, boxes, BVH) and rendering (wall_seconds), the process's wall
time and peak resident memory (its own rusage, from wait4), and the scene's memory per primitive by
structure before any bound is computed (memory.bytes_per_primitive: renderer/render.h, SceneBytes).
Python 3 standard library only. Run nothing else on the machine while timing.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def run(affray, scene, threads):
    cmd = [affray, "render", scene, "-o", scene[:-4] + ".exr", "--stats", "--quiet", "--threads", str(threads)]
    start = time.monotonic()
    child = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, cwd=ROOT)
    out = child.stdout.read()
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.monotonic() - start
    if status != 0:
        return None, wall, usage.ru_maxrss / 1024.0
    return json.loads(out.decode().splitlines()[-1]), wall, usage.ru_maxrss / 1024.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--affray", default=os.path.join(ROOT, "build", "tools", "affray"))
    ap.add_argument("--sizes", default="100,316,1000")
    ap.add_argument("--subdivision", default="316", help="sizes of the subdivision hills ('' for none)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--json")
    a = ap.parse_args()
    scenes = [(int(n), False) for n in a.sizes.split(",") if n]
    scenes += [(int(n), True) for n in a.subdivision.split(",") if n]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n, subdivision in scenes:
            path = os.path.join(tmp, "hill%d%s.rib" % (n, "s" if subdivision else ""))
            gen = [sys.executable, os.path.join(HERE, "gen_hill.py"), str(n), path]
            if subdivision:
                gen.append("--subdivision")
            subprocess.run(gen, check=True, stderr=subprocess.DEVNULL)
            stats, wall, peak = run(a.affray, path, a.threads)
            os.remove(path)
            kind = "subdivision" if subdivision else "polygons"
            if stats is None:
                rows.append({"scene": "%s %dx%d" % (kind, n, n), "failed": True, "wall": wall, "peak_mb": peak})
                continue
            # (An affray from before these figures existed gives none: "-".)
            rows.append({"scene": "%s %dx%d" % (kind, n, n), "faces": n * n, "read": stats.get("read_seconds"),
                         "prepare": stats.get("prepare_seconds"), "render": stats["wall_seconds"], "wall": wall,
                         "peak_mb": peak, "primitives": stats["memory"].get("primitives"),
                         "bytes": stats["memory"].get("bytes_per_primitive")})
    print("| scene | faces | primitives | read | prepare | render | process wall | peak memory | bytes per primitive |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r.get("failed"):
            print("| %s | failed after %.1f s | | | | | | %.0f MB | |" % (r["scene"], r["wall"], r["peak_mb"]))
            continue
        def fmt(x, f):
            return "-" if x is None else f % x
        print("| %s | %d | %s | %s | %s | %.2f s | %.1f s | %.0f MB | %s |" % (
            r["scene"], r["faces"], fmt(r["primitives"], "%d"), fmt(r["read"], "%.2f s"), fmt(r["prepare"], "%.2f s"),
            r["render"], r["wall"], r["peak_mb"], fmt(r["bytes"], "%.0f")))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
