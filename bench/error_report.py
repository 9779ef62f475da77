#!/usr/bin/env python3
"""bench/error_report.py: how image error trades against run time.

For each scene (smooth wave, noisy terrain, thin needles) and each bound mode (affine,
interval, reduced affine), renders at a sweep of pixel tolerances and records wall time, peak memory, regions
bounded per ray, image RMSE and largest error against a converged reference (affine at a
tolerance far below the sweep's), the largest certified geometric error and the depth-limit
hits. Beside them, the tessellation baseline (bench/tessellation_bench.cpp, docs/tessellation.md)
renders the same scene, samples, shading and shadows through an Embree mesh of an N x N grid per
primitive, at a sweep of N. Writes a CSV, a PNG plot (RMSE against time and against peak memory,
one curve per scene and method), prints a Markdown table and, per scene, the crossover: for
each affray setting, the coarsest tessellation with an equal or lower RMSE and what it costs.

    python3 bench/error_report.py [--build build] [--size 96x72] [--out docs/error_report]
                                  [--grids 64,128,256,512,1024,2048]

Needs a Release build of `affray` and, for the plot, python3-matplotlib
(`sudo apt-get install python3-matplotlib`); the tessellation series needs the build's
`bench/affray_bench_tessellation` (built only where CMake found Embree 3) and is skipped with a
note without it. Run from anywhere; renders go to a temporary directory. Every render of one
scene uses the same image size, camera and lights (the scene's RIB with its Format line
replaced), so the only variables are the tolerance and the mode, or the grid.

Times: `wall_seconds` is the time to the image after the scene is read and its shaders compiled:
affray's render (`--stats` wall_seconds), the baseline's tessellation + BVH build + render.
`process_seconds` is the whole process as measured here. `peak_rss_mb` is the peak resident set
of the process (its own rusage, from os.wait4).

Shadows: Renderer::Render starts a shadow ray twice the hit's certified error or the tolerance's
footprint above the hit, whichever is larger. The baseline's hits have no certified error, so its
--tolerance sets that offset alone; by default it is the reference's (--tessellation-tolerance),
so that the baseline's error is its mesh's and not its shadow offset's.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = {"wave": "scenes/wave.rib", "terrain": "scenes/terrain.rib", "needles": "scenes/needles.rib",
          "creature": "scenes/creature.rib",  # creature: a displaced SubdivisionMesh (issue 15)
          # texture maps (issue 16): a ridge one texel wide in a 4096-texel map, and the gallery
          # (a mesh, a plane and a map with noise)
          "ridge": "tests/scenes/stiff/ridge.rib", "textured": "scenes/textured.rib"}
# The CSV's columns: the first nine as before; then peak memory and process time (every row) and
# the tessellation baseline's (its rows only; affray's rows leave them empty, and the
# tessellation rows leave regions_per_ray, max_certified_error and depth_limit_hits empty; their
# tolerance_px is the baseline's --tolerance, which only sets its shadow rays' start).
FIELDS = ["scene", "mode", "tolerance_px", "wall_seconds", "regions_per_ray", "rmse", "max_error",
          "max_certified_error", "depth_limit_hits", "peak_rss_mb", "process_seconds", "grid", "triangles",
          "tessellate_seconds", "bvh_seconds", "render_seconds", "mesh_bytes"]


def run_measured(cmd):
    """Runs `cmd` as a child; returns (exit code, stdout, stderr, seconds, peak RSS in MB). The peak
    RSS is the child's own (os.wait4 returns its rusage; RUSAGE_CHILDREN's ru_maxrss would be the
    largest of all children so far, not this one's)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        child = subprocess.Popen(cmd, cwd=ROOT, stdout=out, stderr=err)
        _, status, usage = os.wait4(child.pid, 0)
        elapsed = time.monotonic() - start
        child.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait again
        out.seek(0)
        err.seek(0)
        return (child.returncode, out.read().decode(errors="replace"), err.read().decode(errors="replace"), elapsed,
                usage.ru_maxrss / 1024.0)  # Linux: kilobytes


def run_stats(cmd):
    """Runs a command that prints its --stats JSON last; returns that JSON with process_seconds
    and peak_rss_mb (measured here) added."""
    code, stdout, stderr, elapsed, peak = run_measured(cmd)
    if code != 0:
        sys.exit(f"failed ({' '.join(cmd)}):\n{stderr}")
    stats = json.loads(stdout.strip().splitlines()[-1])
    stats["process_seconds"] = elapsed
    stats["peak_rss_mb"] = peak
    return stats


def render(affray, rib, out, tolerance, mode, threads, samples):
    """Renders `rib` to `out`; returns the --stats JSON (with the process time and peak RSS
    measured here too)."""
    # Mode "newton": the default reduced affine bounds with certified Newton hits (render --newton).
    bounds = "reduced" if mode == "newton" else mode
    cmd = [affray, "render", rib, "-o", out, "--tolerance", str(tolerance), "--bounds", bounds, "--stats", "--quiet",
           "--samples", str(samples)]
    if mode == "newton":
        cmd.append("--newton")
    if threads:
        cmd += ["--threads", str(threads)]
    return run_stats(cmd)


def tessellate(bench, rib, out, grid, tolerance, threads, samples):
    """Renders `rib` to `out` through the tessellation baseline at an N x N grid per primitive;
    `tolerance` sets only where its shadow rays start (twice its footprint above the hit)."""
    cmd = [bench, rib, "--grid", str(grid), "-o", out, "--tolerance", str(tolerance), "--stats", "--quiet",
           "--samples", str(samples)]
    if threads:
        cmd += ["--threads", str(threads)]
    return run_stats(cmd)


def diff(affray, reference, test):
    done = subprocess.run([affray, "diff", reference, test], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"diff failed: {done.stderr}")
    return json.loads(done.stdout)


def sized_scene(path, width, height, directory):
    """A copy of the scene at `width` x `height` (its aspect ratio kept by the camera's fov), in
    `directory`, reading shaders and maps from the original's directory first."""
    with open(os.path.join(ROOT, path)) as f:
        text = f.read()
    text, count = re.subn(r"^Format\s+\d+\s+\d+\s+[\d.]+", f"Format {width} {height} 1", text, flags=re.M)
    if count != 1:
        sys.exit(f"{path}: expected one Format line")
    # The copy finds the shaders and maps beside the original first, as the original does.
    here = os.path.dirname(os.path.join(ROOT, path))
    text = f'Option "searchpath" "shader" ["{here}:@"] "texture" ["{here}"]\n' + text
    copy = os.path.join(directory, os.path.basename(path))
    with open(copy, "w") as f:
        f.write(text)
    return copy


def plot(rows, path):
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("no plot: python3-matplotlib is not installed (sudo apt-get install python3-matplotlib)", file=sys.stderr)
        return False
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    styles = {"affine": "-o", "reduced": "-.d", "interval": "--s", "newton": "-*", "tessellation": ":^"}
    colours = {"wave": "tab:blue", "terrain": "tab:brown", "needles": "tab:green", "creature": "tab:purple"}
    panels = [(axes[0], "wall_seconds", "time to image (s)", "Error against run time"),
              (axes[1], "peak_rss_mb", "peak memory, process RSS (MB)", "Error against peak memory")]
    for ax, xkey, xlabel, title in panels:
        for scene in dict.fromkeys(r["scene"] for r in rows):
            for mode in dict.fromkeys(r["mode"] for r in rows):
                curve = [r for r in rows if r["scene"] == scene and r["mode"] == mode]
                if not curve:
                    continue
                xs = [r[xkey] for r in curve]
                ys = [max(r["rmse"], 1e-5) for r in curve]  # an exact match would vanish on a log axis
                ax.plot(xs, ys, styles.get(mode, "-"), color=colours.get(scene), label=f"{scene}, {mode}")
                for r, x, y in zip(curve, xs, ys):
                    label = f"N{r['grid']}" if mode == "tessellation" else f"{r['tolerance_px']:g}"
                    ax.annotate(label, (x, y), textcoords="offset points", xytext=(4, 3), fontsize=6)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("image RMSE against the converged reference")
        ax.set_title(f"{title}\n(labels: pixel tolerance, or N of an N x N tessellation)", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return True


def crossover(rows, scene):
    """Lines saying, for each affray setting on `scene`, the coarsest tessellation whose RMSE is
    equal or lower, with its time and memory as multiples of affray's."""
    tess = sorted((r for r in rows if r["scene"] == scene and r["mode"] == "tessellation"), key=lambda r: r["grid"])
    lines = []
    for r in rows:
        if r["scene"] != scene or r["mode"] == "tessellation":
            continue
        head = (f"  {r['mode']} {r['tolerance_px']:g} px: RMSE {r['rmse']:.4f} in {r['wall_seconds']:.2f} s, "
                f"{r['peak_rss_mb']:.0f} MB -> ")
        match = [t for t in tess if t["rmse"] <= r["rmse"]]
        if not match:
            best = min(tess, key=lambda t: t["rmse"])
            lines.append(head + f"no tessellation up to N={tess[-1]['grid']} (best: N={best['grid']}, "
                         f"RMSE {best['rmse']:.4f}, {best['wall_seconds']:.2f} s, {best['peak_rss_mb']:.0f} MB)")
            continue
        t = min(match, key=lambda t: t["wall_seconds"])
        time_ratio = t["wall_seconds"] / r["wall_seconds"] if r["wall_seconds"] > 0 else float("inf")
        memory_ratio = t["peak_rss_mb"] / r["peak_rss_mb"] if r["peak_rss_mb"] > 0 else float("inf")
        lines.append(head + f"tessellation N={t['grid']}: RMSE {t['rmse']:.4f} in {t['wall_seconds']:.2f} s "
                     f"({time_ratio:.2g}x the time), {t['peak_rss_mb']:.0f} MB ({memory_ratio:.2g}x the memory)")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="CMake build directory (Release)")
    parser.add_argument("--size", default="96x72", help="image size WxH (default 96x72)")
    parser.add_argument("--scenes", default="wave,terrain,needles")
    parser.add_argument("--modes", default="reduced,affine,interval",
                        help="bound modes (reduced, affine, interval) and newton (reduced with --newton)")
    parser.add_argument("--tolerances", default="4,2,1,0.5,0.25,0.1", help="pixel tolerances to sweep")
    parser.add_argument("--reference-tolerance", type=float, default=0.02)
    parser.add_argument("--reference-mode", default="affine",
                        help="the reference's mode: affine (its shadow rays start twice the tolerance's footprint "
                             "above the hit, as the tessellation baseline's do) or newton (certified hits and "
                             "shadow rays without that offset: the exact terminators)")
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--samples", type=int, default=1,
                        help="N x N samples per pixel, the same in the reference (default 1: the error "
                             "measured is the tolerance's, not the sampling's)")
    parser.add_argument("--grids", default="64,128,256,512,1024,2048",
                        help="N of the N x N tessellations of the baseline (empty: no tessellation series)")
    parser.add_argument("--tessellation-tolerance", type=float, default=None,
                        help="the baseline's --tolerance, which only sets how far above a hit its shadow rays "
                             "start (default: --reference-tolerance, the reference's offset, so that its error is "
                             "the mesh's; at 0.5 the offset alone gave wave an RMSE of 0.021 at any N)")
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "error_report"), help="writes OUT.csv and OUT.png")
    args = parser.parse_args()
    if args.tessellation_tolerance is None:
        args.tessellation_tolerance = args.reference_tolerance

    affray = os.path.join(args.build, "tools", "affray")
    if not os.access(affray, os.X_OK):
        sys.exit(f"{affray} not found: build first (cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build)")
    width, height = (int(x) for x in args.size.lower().split("x"))
    tolerances = [float(t) for t in args.tolerances.split(",")]
    grids = [int(n) for n in args.grids.split(",") if n.strip()]
    bench = os.path.join(args.build, "bench", "affray_bench_tessellation")
    skipped = None
    if not grids:
        skipped = "tessellation series skipped: --grids is empty"
    elif not os.access(bench, os.X_OK):
        skipped = (f"tessellation series skipped: {bench} was not built (it needs Embree 3: "
                   "sudo apt-get install libembree-dev, then configure and build again)")
        grids = []
    if skipped:
        print(f"note: {skipped}", file=sys.stderr)
    rows = []
    with tempfile.TemporaryDirectory(prefix="affray_report_") as tmp:
        for scene in args.scenes.split(","):
            rib = sized_scene(SCENES[scene], width, height, tmp)
            reference = os.path.join(tmp, f"{scene}_reference.exr")
            ref = render(affray, rib, reference, args.reference_tolerance, args.reference_mode, args.threads,
                         args.samples)
            print(f"{scene}: reference ({args.reference_mode}, tolerance {args.reference_tolerance:g} px) in "
                  f"{ref['wall_seconds']:.1f} s",
                  file=sys.stderr)
            for mode in args.modes.split(","):
                for tolerance in tolerances:
                    image = os.path.join(tmp, f"{scene}_{mode}_{tolerance:g}.exr")
                    stats = render(affray, rib, image, tolerance, mode, args.threads, args.samples)
                    error = diff(affray, reference, image)
                    row = dict.fromkeys(FIELDS, "")
                    row.update({
                        "scene": scene,
                        "mode": mode,
                        "tolerance_px": tolerance,
                        "wall_seconds": stats["wall_seconds"],
                        "regions_per_ray": stats["regions_per_ray_mean"],
                        "rmse": error["rmse"],
                        "max_error": error["max"],
                        "max_certified_error": stats["max_certified_error"],
                        "depth_limit_hits": stats["depth_limit_hits"],
                        "peak_rss_mb": round(stats["peak_rss_mb"], 1),
                        "process_seconds": round(stats["process_seconds"], 3),
                    })
                    rows.append(row)
                    print(f"  {mode} {tolerance:g} px: {row['wall_seconds']:.2f} s, {row['peak_rss_mb']:.0f} MB, "
                          f"rmse {row['rmse']:.4g}", file=sys.stderr)
            for grid in grids:
                image = os.path.join(tmp, f"{scene}_tessellation_{grid}.exr")
                stats = tessellate(bench, rib, image, grid, args.tessellation_tolerance, args.threads, args.samples)
                error = diff(affray, reference, image)
                row = dict.fromkeys(FIELDS, "")
                row.update({
                    "scene": scene,
                    "mode": "tessellation",
                    "tolerance_px": args.tessellation_tolerance,
                    # The time to the image, as affray's wall_seconds: all that follows reading the scene.
                    "wall_seconds": round(stats["tessellate_seconds"] + stats["bvh_seconds"] + stats["render_seconds"], 4),
                    "rmse": error["rmse"],
                    "max_error": error["max"],
                    "peak_rss_mb": round(stats["peak_rss_mb"], 1),
                    "process_seconds": round(stats["process_seconds"], 3),
                    "grid": grid,
                    "triangles": stats["triangles"],
                    "tessellate_seconds": stats["tessellate_seconds"],
                    "bvh_seconds": stats["bvh_seconds"],
                    "render_seconds": stats["render_seconds"],
                    "mesh_bytes": stats["mesh_bytes"],
                })
                rows.append(row)
                print(f"  tessellation N={grid}: {row['wall_seconds']:.2f} s (tessellate {stats['tessellate_seconds']:.2f}, "
                      f"bvh {stats['bvh_seconds']:.2f}, render {stats['render_seconds']:.2f}), "
                      f"{row['peak_rss_mb']:.0f} MB, rmse {row['rmse']:.4g}", file=sys.stderr)

    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out + ".csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    plotted = plot(rows, args.out + ".png")

    print(f"| scene | mode | tolerance (px) | time (s) | peak memory (MB) | regions/ray | RMSE | max error | "
          f"max certified error | depth-limit hits |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r["mode"] == "tessellation":
            print(f"| {r['scene']} | tessellation N={r['grid']} | {r['tolerance_px']:g} | {r['wall_seconds']:.2f} | {r['peak_rss_mb']:.0f} | - | "
                  f"{r['rmse']:.4f} | {r['max_error']:.3f} | - | - |")
        else:
            print(f"| {r['scene']} | {r['mode']} | {r['tolerance_px']:g} | {r['wall_seconds']:.2f} | {r['peak_rss_mb']:.0f} | "
                  f"{r['regions_per_ray']:.1f} | {r['rmse']:.4f} | {r['max_error']:.3f} | {r['max_certified_error']:.3g} | "
                  f"{r['depth_limit_hits']} |")
    if any(r["mode"] == "tessellation" for r in rows):
        print("\nCrossover: for each affray setting, the coarsest tessellation (least time) with an equal or lower RMSE")
        for scene in dict.fromkeys(r["scene"] for r in rows):
            print(f"{scene}:")
            print("\n".join(crossover(rows, scene)))
    elif skipped:
        print(f"\n({skipped})")
    print(f"\nwrote {args.out}.csv" + (f" and {args.out}.png" if plotted else ""), file=sys.stderr)


if __name__ == "__main__":
    main()
