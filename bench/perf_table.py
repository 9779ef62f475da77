#!/usr/bin/env python3
"""bench/perf_table.py: the README's performance tables, regenerated in one run.

    python3 bench/perf_table.py [--build build] [--threads 2] [--base OTHER_BUILD] [--quick]

Renders the benchmark scenes of issue 11 with `affray render --stats --quiet` (a Release build)
and prints two Markdown tables:
  1. per scene: wall time of the render, peak memory of the process (its own rusage), regions
     tested and shader evaluations per camera ray, shadow regions per ray, the bound cache's peak
     size and hit rate, and the thread-seconds spent evaluating bounds (what a cold cache costs);
  2. the wave at frequencies 8 to 1024 (160x120, one sample): time, regions tested and shader
     evaluations per camera ray;
  3. the showcase and the turbulence sphere at --cache-mb 256, 32, 8 and 2: time, peak memory,
     the hierarchies' peak, evictions and bound evaluations (what a smaller budget costs).
With --base, each scene is also rendered by another build (for example the commit before the bound
hierarchy) and the ratio of wall times is printed. Times are this machine's; run nothing else.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SCENES = [
    # (label, scene, extra arguments)
    ("wave 640x480, 1 sample", "scenes/wave.rib", ["--samples", "1"]),
    ("wave 640x480, 2x2 samples", "scenes/wave.rib", []),
    ("wave 640x480, 1 sample, interval bounds", "scenes/wave.rib", ["--samples", "1", "--bounds", "interval"]),
    ("showcase 640x480, 2x2 samples", "scenes/showcase.rib", []),
    ("turbulence (dented) sphere 320x240, 1 sample", "scenes/turbulence.rib", []),
    ("wall 1e-4 thick, 320x384 orthographic, 1 sample", "tests/scenes/stiff/wall.rib", []),
    ("needles 1e-4, 1 sample", "tests/scenes/stiff/needles.rib", ["--samples", "1"]),
    ("amplitude 1000, 1 sample", "tests/scenes/stiff/amp1000.rib", ["--samples", "1"]),
    ("frequency 1000, 1 sample", "tests/scenes/stiff/freq1000.rib", ["--samples", "1"]),
]

# The memory-budget table: these scenes at these --cache-mb values.
BUDGET_SCENES = [
    ("showcase 640x480, 2x2 samples", "scenes/showcase.rib", []),
    ("turbulence sphere 320x240, 1 sample", "scenes/turbulence.rib", []),
]
BUDGETS_MB = (256, 32, 8, 2)


def render(build, scene, extra, threads, outdir):
    exe = os.path.join(build, "tools", "affray")
    out_exr = os.path.join(outdir, "out.exr")
    cmd = [exe, "render", os.path.join(ROOT, scene), "-o", out_exr, "--quiet", "--stats",
           "--threads", str(threads)] + extra
    # Popen + wait4 so that the peak RSS is this child's own.
    child = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    pid = child.pid
    _, status, usage = os.wait4(pid, 0)
    out = child.stdout.read()
    err = child.stderr.read()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit("perf_table.py: failed: %s\n%s" % (" ".join(cmd), err))
    return json.loads(out.strip().splitlines()[-1]), usage.ru_maxrss / 1024.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--base", help="another build to time against (ratio column)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="skip the slow rows of the base build")
    args = ap.parse_args()
    outdir = tempfile.mkdtemp()

    print("| render | wall | peak memory | regions / camera ray | evaluations / camera ray | "
          "shadow regions / ray | cache peak | cache hit rate | bound evaluation (thread-s) |%s" %
          (" base build wall | speed-up |" if args.base else ""))
    print("|---|---|---|---|---|---|---|---|---|%s" % ("---|---|" if args.base else ""))
    for label, scene, extra in SCENES:
        s, rss = render(args.build, scene, extra, args.threads, outdir)
        c = s.get("cache", {})
        row = "| %s | %.2f s | %.0f MB | %.1f | %.3f | %.1f | %.1f MB | %.4f | %.2f |" % (
            label, s["wall_seconds"], rss, s["regions_per_ray_mean"], s.get("evaluations_per_ray_mean", 0),
            s["shadow_regions_per_ray_mean"], c.get("peak_mb", 0), c.get("hit_rate", 0),
            c.get("build_thread_seconds", 0))
        if args.base:
            if args.quick and ("turbulence" in scene or "showcase" in scene or "2x2" in label):
                row += " (skipped) | |"
            else:
                b, _ = render(args.base, scene, extra, args.threads, outdir)
                row += " %.2f s | %.1fx |" % (b["wall_seconds"], b["wall_seconds"] / s["wall_seconds"])
        print(row, flush=True)

    # Scaling with the wave's frequency.
    with open(os.path.join(ROOT, "scenes/wave.rib")) as f:
        wave = f.read()
    print()
    print("| wave frequency | wall | regions / camera ray | evaluations / camera ray | cache peak |")
    print("|---|---|---|---|---|")
    for freq in (8, 16, 32, 64, 128, 256, 512, 1024):
        text = re.sub(r'"frequency" \[[^]]*\]', '"frequency" [%d]' % freq, wave)
        text = re.sub(r"^Format .*$", "Format 160 120 1", text, flags=re.M)
        path = os.path.join(ROOT, "scenes", ".perf_wave_%d.rib" % freq)
        with open(path, "w") as f:
            f.write(text)
        try:
            s, _ = render(args.build, os.path.relpath(path, ROOT), ["--samples", "1"], args.threads, outdir)
        finally:
            os.remove(path)
        print("| %d | %.2f s | %.2f | %.3f | %.1f MB |" % (freq, s["wall_seconds"], s["regions_per_ray_mean"],
                                                          s.get("evaluations_per_ray_mean", 0),
                                                          s.get("cache", {}).get("peak_mb", 0)), flush=True)


    # The memory budget: the hierarchies' share of the peak memory, and what evicting costs.
    print()
    print("| render | --cache-mb | wall | peak memory | cache peak | evictions | bound evaluations | "
          "bound evaluation (thread-s) |")
    print("|---|---|---|---|---|---|---|---|")
    for label, scene, extra in BUDGET_SCENES:
        for mb in BUDGETS_MB:
            s, rss = render(args.build, scene, extra + ["--cache-mb", str(mb)], args.threads, outdir)
            c = s.get("cache", {})
            print("| %s | %g | %.2f s | %.0f MB | %.1f MB | %d | %d | %.2f |" % (
                label, mb, s["wall_seconds"], rss, c.get("peak_mb", 0), c.get("evictions", 0),
                c.get("evaluations", 0), c.get("build_thread_seconds", 0)), flush=True)


if __name__ == "__main__":
    main()
