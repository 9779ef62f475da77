#!/usr/bin/env python3
"""tools/mutate.py: planted faults in the compiler, the VM's number rules, the derivative rules and the
intersector, and whether the tests catch them.

Issue 31, item 2 and issue 33, item 3. The faults come in sets, one module each in tools/mutate_sets/:

  derivatives  Dual<T>'s chain rules, the bound operations they run on, noise and texture slope bounds
  compiler     constant folding, type checks, lowering of operators and builtins, specialisation,
               dead-code pruning, register allocation and emission
  numbers      the interval, affine and reduced affine operations: rounding directions, error terms,
               the fits of the functions, comparisons, noise bounds
  intersector  the renderer's intersector: region culling, nearest-first order, splitting, the
               tolerance and leaf tests, ray-box tests, certified roots

A fault is one exact replacement (file, old text, new text). For each fault the script applies the
edit to a scratch copy of the source tree (never to the repository), rebuilds the set's test binary
there (a few test files of the suite, linked with only the libraries they need; it is added to the
scratch tree's CMakeLists.txt, not the repository's), runs the set's tests and records the fault as
killed (a test fails, the binary crashes or times out) or survived. Survivors are findings:
strengthen the tests, or, if the fault cannot change any result, give the reason in its
`equivalent` field (it is then run, but not counted in the kill rate).

Usage:
    tools/mutate.py --set NAME[,NAME...]|all [--list] [--only FAULT[,FAULT...]] [--jobs N]
                    [--scratch DIR] [--tests SPEC]

The scratch directory (default /tmp/mutate) holds one copy of the working tree and one Release
build (Ninja) per job: src-N, build-N, and the build and test output in log-N.txt. They are reused
between runs and sets, so a second run rebuilds only what changed since. Every build and test run
is under `nice -n 19`, with two compiler processes in all (--jobs 1: two for the one build; --jobs 2:
one each). A mutant is restored in the scratch copy when
it is done, also on Ctrl-C; the repository is only read.
Exit status: 0 when every counted fault was killed, 1 when one survived, 2 on an error (a pattern
that no longer matches exactly once, a mutant or the baseline that does not build, the baseline
failing its tests, an interruption).

Python 3 standard library only.
"""

import argparse
import concurrent.futures
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import mutate_sets  # noqa: E402  (tools/mutate_sets/, found through the line above)

PROG = "mutate"

# ---------------------------------------------------------------------------------------------
# Checking the faults against the tree.


class Error(Exception):
    pass


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def write(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def check_faults(root, fault_set):
    """Every fault's old text occurs exactly once in its file, and differs from its new text; the
    set's test files exist."""
    names = set()
    problems = []
    for f in fault_set.faults:
        if f.name in names:
            problems.append(f"{f.name}: the name is used twice")
        names.add(f.name)
        path = os.path.join(root, f.file)
        if not os.path.isfile(path):
            problems.append(f"{f.name}: {f.file} does not exist")
            continue
        count = read(path).count(f.old)
        if count != 1:
            problems.append(f"{f.name}: the old text occurs {count} times in {f.file}, not once:\n    {f.old!r}")
        if f.old == f.new:
            problems.append(f"{f.name}: the new text is the old one")
    for s in fault_set.test_sources:
        if not os.path.isfile(os.path.join(root, s)):
            problems.append(f"test file {s} does not exist")
    if problems:
        raise Error(f"set {fault_set.name}: planted faults that no longer match the tree "
                    f"(fix tools/mutate_sets/{fault_set.name}.py):\n  " + "\n  ".join(problems))


# ---------------------------------------------------------------------------------------------
# The scratch trees.

SUBDIR = "_mutate"
CMAKE_HOOK = f"\n# Added by tools/mutate.py in its scratch copy only.\nadd_subdirectory({SUBDIR})\n"


def small_targets_cmake(sets):
    """One test binary per set, with the suite's flags (tests/CMakeLists.txt)."""
    out = ["# The fault sets' test binaries (tools/mutate.py), with the suite's flags (tests/CMakeLists.txt).",
           "find_package(Catch2 2 REQUIRED)",
           "set_source_files_properties(${PROJECT_SOURCE_DIR}/tests/main.cpp PROPERTIES COMPILE_OPTIONS",
           '                            "-O0;-g0;-Wno-maybe-uninitialized")']
    for s in sets:
        t = s.target
        sources = " ".join("${PROJECT_SOURCE_DIR}/" + p for p in ["tests/main.cpp"] + s.test_sources)
        libraries = " ".join(s.libraries)
        out.append(f"""
add_executable({t} {sources})
target_compile_options({t} PRIVATE -O1)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options({t} PRIVATE -Wno-array-bounds -Wno-stringop-overflow -Wno-stringop-overread)
endif()
target_include_directories({t} PRIVATE ${{PROJECT_SOURCE_DIR}})
target_link_libraries({t} PRIVATE {libraries} Catch2::Catch2)
target_compile_definitions({t} PRIVATE AFFRAY_SOURCE_DIR="${{PROJECT_SOURCE_DIR}}"
                           AFFRAY_CLI="$<TARGET_FILE:affray>")""")
        if s.cli:  # tests/test_util.h names the program; only a set that runs it has it rebuilt
            out.append(f"add_dependencies({t} affray)")
    return "\n".join(out) + "\n"


def repository_files(root):
    out = subprocess.run(["git", "ls-files", "-z", "-co", "--exclude-standard"], cwd=root, check=True,
                         capture_output=True).stdout
    return [p for p in out.decode().split("\0") if p and os.path.isfile(os.path.join(root, p))]


def put(path, text):
    """Writes text to path unless it holds it already (an unchanged file keeps its time stamp, so
    the build does not redo its dependents)."""
    if os.path.isfile(path) and read(path) == text:
        return
    os.makedirs(os.path.dirname(path), exist_ok=True)
    write(path, text)


def sync_tree(root, src):
    """Makes src a copy of the repository's working tree (tracked and untracked files, not the
    ignored ones), copying only what differs, plus the small targets."""
    os.makedirs(src, exist_ok=True)
    wanted = set(repository_files(root))
    for rel in sorted(wanted):
        a, b = os.path.join(root, rel), os.path.join(src, rel)
        if rel == "CMakeLists.txt":
            put(b, read(a) + CMAKE_HOOK)
            continue
        if os.path.isfile(b):
            with open(a, "rb") as fa, open(b, "rb") as fb:
                if fa.read() == fb.read():
                    continue
        os.makedirs(os.path.dirname(b), exist_ok=True)
        shutil.copyfile(a, b)  # a new time stamp, unlike copy2: the build sees the change
        shutil.copymode(a, b)
    # Files the repository no longer has (a stale test file would still be globbed by CMake).
    for dirpath, dirnames, filenames in os.walk(src):
        rel_dir = os.path.relpath(dirpath, src)
        if rel_dir.split(os.sep)[0] in (SUBDIR, ".git"):
            continue
        for name in filenames:
            rel = os.path.normpath(os.path.join(rel_dir, name))
            if rel not in wanted:
                os.remove(os.path.join(dirpath, name))
    put(os.path.join(src, SUBDIR, "CMakeLists.txt"), small_targets_cmake(mutate_sets.all_sets()))


# The processes running now (each the leader of its own process group), and whether the run was
# interrupted: then no new one starts, and the running ones are killed.
ACTIVE = set()
ACTIVE_LOCK = threading.Lock()
STOP = threading.Event()


def kill_active():
    with ACTIVE_LOCK:
        for p in ACTIVE:
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass


def run_logged(cmd, log, cwd=None, timeout=None):
    """Runs cmd under `nice -n 19` with its output appended to the file log; returns its exit status
    (None on timeout or interruption)."""
    if STOP.is_set():
        return None
    with open(log, "a") as out:
        out.write("$ " + " ".join(cmd) + "\n")
        out.flush()
        # A process group of its own, so that a timeout kills the whole of it (ninja and its compilers).
        p = subprocess.Popen(["nice", "-n", "19"] + cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                             start_new_session=True)
        with ACTIVE_LOCK:
            ACTIVE.add(p)
        try:
            status = p.wait(timeout=timeout)
            return None if STOP.is_set() else status
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
            return None
        finally:
            with ACTIVE_LOCK:
                ACTIVE.discard(p)


# Compiler processes per build: the machine's two cores shared by the jobs (--jobs 2: one each).
BUILD_PARALLEL = 1


def build(src, build_dir, target, log):
    if not os.path.isfile(os.path.join(build_dir, "build.ninja")):
        status = run_logged(["cmake", "-S", src, "-B", build_dir, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                             "-DAFFRAY_TESTS=OFF", "-DAFFRAY_BENCH=OFF"], log)
        if status != 0:
            return False
    return run_logged(["cmake", "--build", build_dir, "--target", target, "--", f"-j{BUILD_PARALLEL}"], log) == 0


# ---------------------------------------------------------------------------------------------
# Running the tests.


class Outcome:
    def __init__(self, status, by=None, build_s=0.0, test_s=0.0):
        self.status = status  # "killed", "survived", "build failed", "error"
        self.by = by or []  # the failing test cases, or how the run ended
        self.build_s = build_s
        self.test_s = test_s


def run_tests(build_dir, target, spec, log, timeout):
    """Runs the set's binary on spec: (passed, the failing test cases or how the run ended)."""
    binary = os.path.join(build_dir, SUBDIR, target)
    with tempfile.NamedTemporaryFile(suffix=".xml", delete=False) as tmp:
        report = tmp.name
    try:
        status = run_logged([binary] + ([spec] if spec else []) + ["--reporter", "xml", "--out", report], log,
                            timeout=timeout)
        if status is None:
            return False, [f"timed out after {timeout:.0f} s" if not STOP.is_set() else "interrupted"]
        failed = []
        try:
            for case in ET.parse(report).getroot().iter("TestCase"):
                result = case.find("OverallResult")
                if result is not None and result.get("success") == "false":
                    failed.append(case.get("name", ""))
        except ET.ParseError:
            pass  # a crash leaves the report unfinished
        if status == 0:
            return True, []
        if status < 0:
            return False, failed + [f"crashed (signal {-status})"]
        return False, failed or [f"exit status {status}"]
    finally:
        os.unlink(report)


def short_name(name):
    """A test case's name, shorter for the table."""
    for long, short in (("conformance: every opcode over random regions - ", "regions "),
                        ("conformance: every opcode on edge values - ", "edges "), ("vm::", ""),
                        ("regression: ", "regression ")):
        name = name.replace(long, short)
    return name


# ---------------------------------------------------------------------------------------------
# The run.


class Worker:
    """One scratch source tree and its build: applies a fault, builds, tests, restores."""

    def __init__(self, scratch, index):
        self.src = os.path.join(scratch, f"src-{index}")
        self.build = os.path.join(scratch, f"build-{index}")
        self.log = os.path.join(scratch, f"log-{index}.txt")

    def prepare(self, target):
        sync_tree(ROOT, self.src)
        return build(self.src, self.build, target, self.log)

    def run(self, fault, target, spec, timeout):
        path = os.path.join(self.src, fault.file)
        original = read(path)
        if original.count(fault.old) != 1:
            return Outcome("error", ["the old text does not occur exactly once in the scratch copy"])
        with open(self.log, "a") as out:
            out.write(f"\n===== {fault.name}\n")
        try:
            write(path, original.replace(fault.old, fault.new))
            t0 = time.monotonic()
            built = build(self.src, self.build, target, self.log)
            t1 = time.monotonic()
            if not built:
                return Outcome("build failed", [f"see {self.log}"], t1 - t0)
            passed, by = run_tests(self.build, target, spec, self.log, timeout)
            t2 = time.monotonic()
            return Outcome("survived" if passed else "killed", by, t1 - t0, t2 - t1)
        finally:
            write(path, original)  # the scratch copy only; the next build redoes its dependents


class Summary:
    def __init__(self, fault_set, faults, results, minutes):
        counted = [f for f in faults if not f.equivalent]
        self.name = fault_set.name
        self.faults = len(faults)
        self.equivalent = len(faults) - len(counted)
        self.killed = sum(1 for f in counted if results[f.name].status == "killed")
        self.survived = [f.name for f in counted if results[f.name].status == "survived"]
        self.errors = [f.name for f in faults if results[f.name].status in ("build failed", "error")]
        self.rate = 100.0 * self.killed / len(counted) if counted else 100.0
        self.counted = len(counted)
        self.minutes = minutes


def run_set(fault_set, faults, args, workers):
    """Runs faults of fault_set; returns its Summary, or None on an error before the mutants."""
    target = fault_set.target
    spec = args.tests or fault_set.test_spec
    width = max(len(f.name) for f in faults)
    print(f"== Set {fault_set.name}: {len(faults)} faults; baseline: {len(workers)} scratch tree(s) in "
          f"{args.scratch}, building {target} ...", flush=True)
    t0 = time.monotonic()
    for w in workers:
        if not w.prepare(target):
            print(f"{PROG}: the baseline does not build (see {w.log})", file=sys.stderr)
            return None
    build_s = time.monotonic() - t0
    t1 = time.monotonic()
    passed, by = run_tests(workers[0].build, target, spec, workers[0].log, timeout=3600)
    base_s = time.monotonic() - t1
    if not passed:
        print(f"{PROG}: the baseline fails its tests ({', '.join(by)}; see {workers[0].log})", file=sys.stderr)
        return None
    print(f"Baseline built in {build_s:.0f} s, tests pass in {base_s:.0f} s.", flush=True)
    timeout = max(60.0, 5 * base_s)

    results = {}
    lock = threading.Lock()
    free = list(workers)

    def one(fault):
        with lock:
            w = free.pop()
        try:
            outcome = w.run(fault, target, spec, timeout) if not STOP.is_set() else Outcome("error", ["interrupted"])
        finally:
            with lock:
                free.append(w)
        with lock:
            results[fault.name] = outcome
            print(f"  {fault.name:{width}} {outcome.status:12} build {outcome.build_s:4.0f} s, "
                  f"tests {outcome.test_s:4.0f} s, {len(outcome.by)} failing", flush=True)
        return outcome

    t2 = time.monotonic()
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=len(workers))
    try:
        for future in [pool.submit(one, f) for f in faults]:
            future.result()
    except KeyboardInterrupt:
        STOP.set()
        kill_active()
        pool.shutdown(wait=True, cancel_futures=True)
        raise
    pool.shutdown()
    total_s = time.monotonic() - t2

    print()
    print(f"{'fault':{width}} {'file':34} {'result':10} failing test cases")
    for f in faults:
        o = results[f.name]
        status = o.status + (" (equivalent)" if f.equivalent else "")
        by = [short_name(n) for n in o.by]
        if len(by) > 4:
            by = by[:4] + [f"{len(by) - 4} more"]
        print(f"{f.name:{width}} {f.file:34} {status:10} {'; '.join(by)}")
    s = Summary(fault_set, faults, results, total_s / 60)
    print()
    print(f"Set {s.name}: kill rate {s.killed}/{s.counted} = {s.rate:.1f} % of the counted faults "
          f"({s.equivalent} equivalent, not counted); {total_s / 60:.1f} min for {len(faults)} mutants, "
          f"{total_s / max(1, len(faults)):.0f} s each on average, {len(workers)} job(s).", flush=True)
    if s.survived:
        print("Survived: " + ", ".join(s.survived))
    if s.errors:
        print("Errors: " + ", ".join(s.errors), file=sys.stderr)
    return s


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--set", default="all",
                        help=f"the fault sets to run: {', '.join(mutate_sets.NAMES)} or all (the default)")
    parser.add_argument("--list", action="store_true", help="list the faults and exit")
    parser.add_argument("--only", metavar="FAULT[,FAULT...]", help="run only these faults (of the sets chosen)")
    parser.add_argument("--jobs", type=int, default=1, help="mutants built and tested at once (one scratch tree each)")
    parser.add_argument("--scratch", default="/tmp/mutate", help="scratch directory (default /tmp/mutate)")
    parser.add_argument("--tests", help="Catch2 test spec instead of the set's own (one set only)")
    args = parser.parse_args()

    def interrupted(signum, frame):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, interrupted)

    names = mutate_sets.NAMES if args.set == "all" else args.set.split(",")
    unknown = [n for n in names if n not in mutate_sets.NAMES]
    if unknown:
        print(f"{PROG}: no set named {', '.join(unknown)} (sets: {', '.join(mutate_sets.NAMES)})", file=sys.stderr)
        return 2
    if args.tests and len(names) != 1:
        print(f"{PROG}: --tests needs one set", file=sys.stderr)
        return 2
    sets = [mutate_sets.load(n) for n in names]
    try:
        for s in sets:
            check_faults(ROOT, s)
    except Error as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 2
    chosen = [(s, list(s.faults)) for s in sets]
    if args.only:
        wanted = args.only.split(",")
        known = {f.name for s in sets for f in s.faults}
        missing = [n for n in wanted if n not in known]
        if missing:
            print(f"{PROG}: no fault named {', '.join(missing)} in the sets chosen (--list lists them)",
                  file=sys.stderr)
            return 2
        chosen = [(s, [f for f in fs if f.name in wanted]) for s, fs in chosen]
        chosen = [(s, fs) for s, fs in chosen if fs]
    if args.list:
        for s, fs in chosen:
            width = max(len(f.name) for f in fs)
            print(f"== {s.name} ({len(fs)}): {s.what}; tests {s.test_spec}")
            for f in fs:
                tag = "  (equivalent: not counted)" if f.equivalent else ""
                print(f"{f.name:{width}} {f.file}: {f.what}{tag}")
        return 0

    jobs = max(1, args.jobs)
    global BUILD_PARALLEL
    BUILD_PARALLEL = max(1, 2 // jobs)
    os.makedirs(args.scratch, exist_ok=True)
    workers = [Worker(args.scratch, i) for i in range(jobs)]
    for w in workers:
        if os.path.exists(w.log):
            os.remove(w.log)
    summaries = []
    t0 = time.monotonic()
    try:
        for s, fs in chosen:
            summary = run_set(s, fs, args, workers[:min(jobs, len(fs))])
            if summary is None:
                return 2
            summaries.append(summary)
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted (the scratch copies are restored; the repository was never touched)",
              file=sys.stderr)
        return 2
    total_min = (time.monotonic() - t0) / 60

    print()
    print("| Set | Faults | Killed | Equivalent | Kill rate | Minutes |")
    print("|---|---:|---:|---:|---:|---:|")
    for s in summaries:
        print(f"| {s.name} | {s.faults} | {s.killed} | {s.equivalent} | {s.killed}/{s.counted} = {s.rate:.0f} % "
              f"| {s.minutes:.0f} |")
    print(f"{total_min:.1f} min in all, {jobs} job(s).")
    if any(s.errors for s in summaries):
        return 2
    return 1 if any(s.survived for s in summaries) else 0


if __name__ == "__main__":
    sys.exit(main())
