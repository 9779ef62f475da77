#!/usr/bin/env python3
"""bench/real/run.py: renders the real-scene benchmark set and prints one Markdown table.

    python3 bench/real/run.py [--affray build/tools/affray] [--scenes a,b,...] [--threads 2]
                              [--time-limit 120] [--crop XMIN,XMAX,YMIN,YMAX] [--json OUT.json]

Each scene is rendered once, one after the other, with `affray render SCENE -o TMP.exr --stats
--quiet --threads N --time-limit S` (Python 3 standard library only). The table gives per scene:
the render's wall time (affray's wall_seconds: tracing the image, after the scene is read, its
shaders compiled, its maps made and its surfaces prepared; a render stopped by --time-limit shows
how far it got instead), the whole process's wall time (all of that included), the peak resident
memory of the affray process (its own rusage, from wait4),
region bounds tested and bounds evaluated (by running the shader) per camera ray and per shadow
ray, depth-limit hits, rays out of region budget, the largest certified error of a camera hit
(world units), and the share of the render spent evaluating bounds:
cache.build_thread_seconds / (wall_seconds * threads).

The images are written to a temporary directory and deleted. Run nothing else on the machine
while timing. --crop renders a window of each image only (quick checks). The first run after a
checkout also makes the texture maps the scenes' MakeTexture requests ask for (kept next to
their pictures, and made again only when a picture is newer).
"""
import argparse
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SCENES = ["teapot_dented", "subdiv_noise", "nurbs_textured", "heightfield", "emboss_teapot"]


def render(affray, scene, threads, time_limit, crop, outdir):
    """Renders one scene; returns (stats or None, exit status, the last error line, peak RSS of
    the affray process in MB, seconds)."""
    name = os.path.basename(scene)[:-4]
    out = os.path.join(outdir, name + ".exr")
    cmd = [affray, "render", scene, "-o", out, "--stats", "--quiet", "--threads", str(threads),
           "--time-limit", "%g" % time_limit]
    if crop:
        cmd += ["--crop", crop]
    start = time.monotonic()
    with open(os.path.join(outdir, name + ".stdout"), "w+") as so, \
            open(os.path.join(outdir, name + ".stderr"), "w+") as se:
        # Its own process group, so that a render still running well past its time limit (it
        # should not happen) is ended whole rather than hanging the benchmark.
        child = subprocess.Popen(cmd, stdout=so, stderr=se, cwd=ROOT, start_new_session=True)
        deadline = start + time_limit + 120
        killed = False
        while True:
            pid, wstatus, usage = os.wait4(child.pid, os.WNOHANG)
            if pid == child.pid:
                break
            if not killed and time.monotonic() > deadline:
                os.killpg(child.pid, signal.SIGTERM)
                killed = True
            time.sleep(0.1)
        child.returncode = os.waitstatus_to_exitcode(wstatus)
        so.seek(0)
        se.seek(0)
        stdout, stderr = so.read(), se.read()
    seconds = time.monotonic() - start
    stats = None
    for line in stdout.splitlines():
        line = line.strip()
        if line.startswith("{"):
            stats = json.loads(line)  # with several frames rendered, the last one
    errors = [l for l in stderr.splitlines() if ": error: " in l]
    # ru_maxrss is in kilobytes on Linux: this child's own peak, not the largest child's so far.
    return stats, child.returncode, (errors[0] if errors else ""), usage.ru_maxrss / 1024.0, seconds


def fmt(v, spec):
    return "-" if v is None else spec % v


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--affray", default=os.path.join(ROOT, "build", "tools", "affray"))
    ap.add_argument("--scenes", default=",".join(SCENES),
                    help="comma-separated scene names (of bench/real) or RIB paths")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--time-limit", type=float, default=120, help="seconds per scene (affray's --time-limit)")
    ap.add_argument("--crop", help="render only this window of each image: XMIN,XMAX,YMIN,YMAX")
    ap.add_argument("--json", help="also write every scene's raw --stats record to this file")
    args = ap.parse_args()
    affray = os.path.abspath(args.affray)
    if not os.access(affray, os.X_OK):
        sys.exit("run.py: no affray at %s (build it, or give --affray)" % affray)

    scenes = []
    for name in args.scenes.split(","):
        name = name.strip()
        path = name if name.endswith(".rib") else os.path.join(HERE, name + ".rib")
        if not os.path.exists(path):
            sys.exit("run.py: no scene %s" % path)
        scenes.append(os.path.abspath(path))

    try:
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
    except OSError:
        commit, dirty = "unknown", ""
    version = subprocess.run([affray, "--version"], capture_output=True, text=True).stdout.strip()
    limit = "%g" % args.time_limit
    print("%s, commit %s%s, %d threads, time limit %s s per scene%s" % (
        version, commit, " (modified)" if dirty else "", args.threads, limit,
        ", crop " + args.crop if args.crop else ""))
    print()
    print("| scene | render wall | process wall | peak memory | regions / camera ray | evaluations / camera ray | "
          "regions / shadow ray | evaluations / shadow ray | depth-limit hits | budget-exhausted rays | "
          "max certified error | bound evaluation share |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    outdir = tempfile.mkdtemp(prefix="affray-bench-real-")
    records = {}
    try:
        for scene in scenes:
            name = os.path.basename(scene)[:-4]
            stats, status, error, rss, seconds = render(affray, scene, args.threads, args.time_limit,
                                                        args.crop, outdir)
            records[name] = {"status": status, "peak_rss_mb": rss, "seconds": seconds, "stats": stats,
                             "error": error}
            if stats is None or status != 0:
                if status == 4 and "wall-clock" in error:
                    m = re.search(r"(\d+) of (\d+) tiles", error)
                    what = "time limit (%s s)%s" % (limit, ": %s of %s tiles" % m.groups() if m else "")
                elif status in (130, 143, -signal.SIGTERM):
                    what = "killed after %.0f s" % seconds
                else:
                    message = error.split(": error: ", 1)[-1].split(" (", 1)[0]
                    what = "failed (exit %s): %s" % (status, message[:100])
                print("| %s | %s | %.1f s | %.0f MB | - | - | - | - | - | - | - | - |" % (name, what, seconds, rss),
                      flush=True)
                continue
            wall = stats["wall_seconds"]
            cache = stats.get("cache", {})
            share = cache.get("build_thread_seconds", 0) / (wall * args.threads) if wall > 0 else None
            print("| %s | %.1f s | %.1f s | %.0f MB | %s | %s | %s | %s | %d | %d | %s | %s |" % (
                name, wall, seconds, rss, fmt(stats.get("regions_per_ray_mean"), "%.1f"),
                fmt(stats.get("evaluations_per_ray_mean"), "%.2f"),
                fmt(stats.get("shadow_regions_per_ray_mean"), "%.1f"),
                fmt(stats.get("shadow_evaluations_per_ray_mean"), "%.2f"),
                stats.get("depth_limit_hits", 0), stats.get("budget_exhausted_rays", 0),
                fmt(stats.get("max_certified_error"), "%.3g"),
                "-" if share is None else "%.0f %%" % (100 * share)), flush=True)
    finally:
        shutil.rmtree(outdir, ignore_errors=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(records, f, indent=1)


if __name__ == "__main__":
    main()
