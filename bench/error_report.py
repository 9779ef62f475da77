#!/usr/bin/env python3
"""bench/error_report.py: how image error trades against run time.

For each scene (smooth wave, noisy terrain, thin needles) and each bound mode (affine,
interval), renders at a sweep of pixel tolerances and records wall time, regions bounded per
ray, image RMSE and largest error against a converged reference (affine at a tolerance far
below the sweep's), the largest certified geometric error and the depth-limit hits. Writes a
CSV, a PNG plot (RMSE against time, one curve per scene and mode) and prints a Markdown table.

    python3 bench/error_report.py [--build build] [--size 96x72] [--out docs/error_report]

Needs a Release build of `affray` and, for the plot, python3-matplotlib
(`sudo apt-get install python3-matplotlib`). Run from anywhere; renders go to a temporary
directory. Every render of one scene uses the same image size, camera and lights (the scene's
RIB with its Format line replaced), so the only variables are the tolerance and the mode.
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
SCENES = {"wave": "scenes/wave.rib", "terrain": "scenes/terrain.rib", "needles": "scenes/needles.rib"}


def render(affray, rib, out, tolerance, mode, threads, samples):
    """Renders `rib` to `out`; returns the --stats JSON (with the wall time measured here too)."""
    cmd = [affray, "render", rib, "-o", out, "--tolerance", str(tolerance), "--bounds", mode, "--stats", "--quiet",
           "--samples", str(samples)]
    if threads:
        cmd += ["--threads", str(threads)]
    start = time.monotonic()
    done = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    elapsed = time.monotonic() - start
    if done.returncode != 0:
        sys.exit(f"render failed ({' '.join(cmd)}):\n{done.stderr}")
    stats = json.loads(done.stdout.strip().splitlines()[-1])
    stats["process_seconds"] = elapsed
    return stats


def diff(affray, reference, test):
    done = subprocess.run([affray, "diff", reference, test], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"diff failed: {done.stderr}")
    return json.loads(done.stdout)


def sized_scene(path, width, height, directory):
    """A copy of the scene at `width` x `height` (its aspect ratio kept by the camera's fov)."""
    with open(os.path.join(ROOT, path)) as f:
        text = f.read()
    text, count = re.subn(r"^Format\s+\d+\s+\d+\s+[\d.]+", f"Format {width} {height} 1", text, flags=re.M)
    if count != 1:
        sys.exit(f"{path}: expected one Format line")
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
    fig, ax = plt.subplots(figsize=(7.5, 5))
    styles = {"affine": "-o", "interval": "--s"}
    colours = {"wave": "tab:blue", "terrain": "tab:brown", "needles": "tab:green"}
    for scene in dict.fromkeys(r["scene"] for r in rows):
        for mode in dict.fromkeys(r["mode"] for r in rows):
            curve = [r for r in rows if r["scene"] == scene and r["mode"] == mode]
            if not curve:
                continue
            xs = [r["wall_seconds"] for r in curve]
            ys = [max(r["rmse"], 1e-5) for r in curve]  # an exact match would vanish on a log axis
            ax.plot(xs, ys, styles.get(mode, "-"), color=colours.get(scene), label=f"{scene}, {mode}")
            for r, x, y in zip(curve, xs, ys):
                ax.annotate(f"{r['tolerance_px']:g}", (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("image RMSE against the converged reference")
    ax.set_title("Error against run time (labels: pixel tolerance)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="CMake build directory (Release)")
    parser.add_argument("--size", default="96x72", help="image size WxH (default 96x72)")
    parser.add_argument("--scenes", default="wave,terrain,needles")
    parser.add_argument("--modes", default="affine,interval")
    parser.add_argument("--tolerances", default="4,2,1,0.5,0.25,0.1", help="pixel tolerances to sweep")
    parser.add_argument("--reference-tolerance", type=float, default=0.02)
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--samples", type=int, default=1,
                        help="N x N samples per pixel, the same in the reference (default 1: the error "
                             "measured is the tolerance's, not the sampling's)")
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "error_report"), help="writes OUT.csv and OUT.png")
    args = parser.parse_args()

    affray = os.path.join(args.build, "tools", "affray")
    if not os.access(affray, os.X_OK):
        sys.exit(f"{affray} not found: build first (cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build)")
    width, height = (int(x) for x in args.size.lower().split("x"))
    tolerances = [float(t) for t in args.tolerances.split(",")]
    rows = []
    with tempfile.TemporaryDirectory(prefix="affray_report_") as tmp:
        for scene in args.scenes.split(","):
            rib = sized_scene(SCENES[scene], width, height, tmp)
            reference = os.path.join(tmp, f"{scene}_reference.exr")
            ref = render(affray, rib, reference, args.reference_tolerance, "affine", args.threads,
                         args.samples)
            print(f"{scene}: reference (affine, tolerance {args.reference_tolerance:g} px) in {ref['wall_seconds']:.1f} s",
                  file=sys.stderr)
            for mode in args.modes.split(","):
                for tolerance in tolerances:
                    image = os.path.join(tmp, f"{scene}_{mode}_{tolerance:g}.exr")
                    stats = render(affray, rib, image, tolerance, mode, args.threads, args.samples)
                    error = diff(affray, reference, image)
                    row = {
                        "scene": scene,
                        "mode": mode,
                        "tolerance_px": tolerance,
                        "wall_seconds": stats["wall_seconds"],
                        "regions_per_ray": stats["regions_per_ray_mean"],
                        "rmse": error["rmse"],
                        "max_error": error["max"],
                        "max_certified_error": stats["max_certified_error"],
                        "depth_limit_hits": stats["depth_limit_hits"],
                    }
                    rows.append(row)
                    print(f"  {mode} {tolerance:g} px: {row['wall_seconds']:.2f} s, rmse {row['rmse']:.4g}", file=sys.stderr)

    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out + ".csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    plotted = plot(rows, args.out + ".png")

    print(f"| scene | mode | tolerance (px) | time (s) | regions/ray | RMSE | max error | max certified error | depth-limit hits |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['scene']} | {r['mode']} | {r['tolerance_px']:g} | {r['wall_seconds']:.2f} | {r['regions_per_ray']:.1f} | "
              f"{r['rmse']:.4f} | {r['max_error']:.3f} | {r['max_certified_error']:.3g} | {r['depth_limit_hits']} |")
    print(f"\nwrote {args.out}.csv" + (f" and {args.out}.png" if plotted else ""), file=sys.stderr)


if __name__ == "__main__":
    main()
