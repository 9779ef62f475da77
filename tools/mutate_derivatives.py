#!/usr/bin/env python3
"""tools/mutate_derivatives.py: planted faults in the derivative rules, and whether the tests catch them.

Issue 31, item 2 ("derivative bounds proven, not assumed"). FAULTS below lists named faults, each one
exact replacement (file, old text, new text) in the rules that give Dual<T> its derivatives and
their bounds: vm/numbers/dual.h's chain rules, the bound types' operations those rules run on
(vm/numbers/interval.*, vm/numbers/reduced_affine.*), the noise bounds (vm/numbers/noise.*) and the
texture slope bounds (vm/texture_lookup.h, texture/lookup.cpp). For each fault the script applies
the edit to a scratch copy of the source tree (never to the repository), rebuilds one small test
binary there, runs the derivative tests and records the fault as killed (a test fails, the binary
crashes or times out) or survived. Survivors are findings: strengthen the tests, or, if the fault
cannot change any result, give the reason in its `equivalent` field (it is then run, but not
counted in the kill rate).

The small binary (affray_derivative_tests) holds TEST_SOURCES and links only the vm and texture
libraries, so that a mutant of a header included everywhere (dual.h, number.h) rebuilds in about
a minute at -j1, not the whole project. It is added to the scratch tree's CMakeLists.txt, not the
repository's. (The other derivative tests, interpreter_test.cpp's finite differences of compiled
shaders and reduced_affine_test.cpp, need the compiler and the renderer: left out.)

Usage:
    tools/mutate_derivatives.py [--list] [--only NAME[,NAME...]] [--jobs N] [--scratch DIR] [--tests SPEC]

The scratch directory (default /tmp/mutate-derivatives) holds one copy of the working tree and one
Release build (Ninja) per job: src-N, build-N, and the build and test output in log-N.txt. They are
reused between runs, so a second run rebuilds only what changed since. Every build and test run is
under `nice -n 19`, one compiler process per job. A mutant is restored in the scratch copy when it
is done, also on Ctrl-C; the repository is only read.
Exit status: 0 when every counted fault was killed, 1 when one survived, 2 on an error (a pattern
that no longer matches exactly once, a mutant or the baseline that does not build, the baseline
failing its tests, an interruption).

Python 3 standard library only.
"""

import argparse
import concurrent.futures
import dataclasses
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

# The test files of the small binary, and what it runs for every mutant (Catch2's test spec: a
# comma is "or"; about 10 s in all).
TEST_SOURCES = [
    "tests/vm/conformance_test.cpp",
    "tests/vm/numbers/dual_test.cpp",
    "tests/vm/numbers/noise_test.cpp",
    "tests/vm/numbers/interval_test.cpp",
    "tests/texture/texture_test.cpp",
]
TEST_SPEC = "[conformance],[dual],[noise],[interval],[texture]"
TARGET = "affray_derivative_tests"


@dataclasses.dataclass(frozen=True)
class Fault:
    name: str
    file: str
    old: str
    new: str
    what: str
    # Why the fault cannot change any result, if it cannot: then it is not counted.
    equivalent: str = ""


FAULTS = [
    # --- vm/numbers/dual.h: the chain rules (every T: Dual<double> and the bounds alike) ----------
    Fault("product-rule-drop-term", "vm/numbers/dual.h",
          "return {a.v * b.v, a.du * b.v + a.v * b.du, a.dv * b.v + a.v * b.dv};",
          "return {a.v * b.v, a.du * b.v, a.dv * b.v + a.v * b.dv};",
          "(ab)' loses a b' in u"),
    Fault("quotient-rule-sign", "vm/numbers/dual.h",
          "return {q, Div(a.du - q * b.du, b.v), Div(a.dv - q * b.dv, b.v)};",
          "return {q, Div(a.du + q * b.du, b.v), Div(a.dv - q * b.dv, b.v)};",
          "(a/b)' = (a' + (a/b) b') / b in u"),
    Fault("reciprocal-rule-sign", "vm/numbers/dual.h",
          "T k = Div(-q, b.v);",
          "T k = Div(q, b.v);",
          "(c/b)' = +(c/b) b' / b"),
    Fault("constant-minus-sign", "vm/numbers/dual.h",
          "return {c - a.v, -a.du, -a.dv};",
          "return {c - a.v, a.du, -a.dv};",
          "(c - a)' = +a' in u"),
    Fault("sqr-factor", "vm/numbers/dual.h",
          "T k = a.v * 2.0;",
          "T k = a.v;",
          "(a^2)' = a a'"),
    Fault("sqrt-factor", "vm/numbers/dual.h",
          "T k = Select(Less(a.v, zero), zero, Div(0.5, s));",
          "T k = Select(Less(a.v, zero), zero, Div(1.0, s));",
          "sqrt(a)' = a' / sqrt(a)"),
    Fault("sqrt-drop-negative-branch", "vm/numbers/dual.h",
          "T k = Select(Less(a.v, zero), zero, Div(0.5, s));",
          "T k = Select(Less(a.v, zero), Div(0.5, s), Div(0.5, s));",
          "sqrt's derivative 0.5/sqrt(a) also where a < 0 (the VM's sqrt is 0 there)"),
    Fault("exp-drop-factor", "vm/numbers/dual.h",
          "return {e, e * a.du, e * a.dv};",
          "return {e, e * a.du, a.dv};",
          "exp(a)' = a' in v"),
    Fault("log-factor", "vm/numbers/dual.h",
          "return {log(a.v), a.du / a.v, a.dv / a.v};",
          "return {log(a.v), a.du / a.v, a.dv * a.v};",
          "log(a)' = a a' in v"),
    Fault("cos-sign", "vm/numbers/dual.h",
          "T s = -sin(a.v);",
          "T s = sin(a.v);",
          "cos(a)' = +sin(a) a'"),
    Fault("tan-factor", "vm/numbers/dual.h",
          "T k = 1.0 + sqr(t);",
          "T k = sqr(t);",
          "tan(a)' = tan^2(a) a' (the 1 dropped)"),
    Fault("abs-sign", "vm/numbers/dual.h",
          "T s = sign(a.v);",
          "T s = abs(sign(a.v));",
          "|a|' = |sign(a)| a'"),
    Fault("pow-exponent", "vm/numbers/dual.h",
          "T k = b.v * Pow(a.v, b.v - 1.0);",
          "T k = b.v * Pow(a.v, b.v);",
          "(a^b)' = b a^b a' + ..."),
    Fault("pow-log-term", "vm/numbers/dual.h",
          "T pl = Select(negative, zero, p * log(a.v));",
          "T pl = Select(negative, zero, log(a.v));",
          "(a^b)' = ... + log(a) b' (the factor a^b dropped)"),
    Fault("pow-negative-base", "vm/numbers/dual.h",
          "k = Select(negative, Select(Equal(floor(b.v), b.v), k, zero), k);",
          "k = Select(negative, zero, k);",
          "a negative base to an integer power: derivative 0 in a"),
    Fault("asin-factor", "vm/numbers/dual.h",
          "T k = Div(1.0, Sqrt(1.0 - sqr(a.v)));",
          "T k = Div(1.0, 1.0 - sqr(a.v));",
          "asin(a)' = a' / (1 - a^2)"),
    Fault("acos-sign", "vm/numbers/dual.h",
          "T k = Div(-1.0, Sqrt(1.0 - sqr(a.v)));",
          "T k = Div(1.0, Sqrt(1.0 - sqr(a.v)));",
          "acos(a)' = +a' / sqrt(1 - a^2)"),
    Fault("atan-factor", "vm/numbers/dual.h",
          "T k = 1.0 / (1.0 + sqr(a.v));",
          "T k = 1.0 / (1.0 + abs(a.v));",
          "atan(a)' = a' / (1 + |a|)"),
    Fault("atan2-sign", "vm/numbers/dual.h",
          "return {v, (x.v * y.du - y.v * x.du) / r2, (x.v * y.dv - y.v * x.dv) / r2};",
          "return {v, (x.v * y.du + y.v * x.du) / r2, (x.v * y.dv - y.v * x.dv) / r2};",
          "atan2(y, x)' = (x y' + y x') / (x^2 + y^2) in u"),
    Fault("atan2-scaled-sign", "vm/numbers/dual.h",
          "return {v, (q * y.du - x.du) * k, (q * y.dv - x.dv) * k};",
          "return {v, (q * y.du + x.du) * k, (q * y.dv - x.dv) * k};",
          "atan2's scaled formula for |y| > |x| (squares that overflow or underflow): + x' in u"),
    Fault("atan2-join-one-side", "vm/numbers/dual.h",
          "if (pick == Truth::False) return g(v);\n    return Join(f(v), g(v));",
          "if (pick == Truth::False) return g(v);\n    return f(v);",
          "a bound undecided between atan2's formulas takes the first's derivatives, not the join",
          equivalent="atan2's three derivative formulas are one function in real arithmetic, and a bound "
          "of any one encloses its real values with outward rounding; the join only keeps the double "
          "of the other formula (a few ulps from the real value) inside where an enclosure is tighter "
          "than that, which no test region reaches: 0 misses in 640,000 points of regions a few ulps "
          "wide straddling m = 2^511, m = 2^-480 and |y| = |x|, Interval and ReducedAffine"),
    Fault("minmax-join-one-side", "vm/numbers/dual.h",
          "return {v, Join(a.du, b.du), Join(a.dv, b.dv)};",
          "return {v, a.du, a.dv};",
          "Min/Max of operands a bound cannot order take a's derivatives, not the join"),
    Fault("max-picks-wrong-operand", "vm/numbers/dual.h",
          "return WithDerivativesOf(Max(a.v, b.v), TruthOf(LessEq(b.v, a.v)), a, b);",
          "return WithDerivativesOf(Max(a.v, b.v), TruthOf(LessEq(a.v, b.v)), a, b);",
          "Max takes the derivatives of the smaller operand"),

    # --- The bound types' operations on the derivative paths ----------------------------------------
    Fault("interval-zero-test-one-end", "vm/numbers/interval.h",
          "friend bool IsExactlyZero(const Interval& x) { return x.m_lo == 0 && x.m_hi == 0; }",
          "friend bool IsExactlyZero(const Interval& x) { return x.m_lo == 0; }",
          "an interval [0, hi] counts as an exactly zero derivative (ChainScale, pow, texture drop it)"),
    Fault("reduced-zero-test-ignores-terms", "vm/numbers/reduced_affine.h",
          "friend bool IsExactlyZero(const ReducedAffine& x) { return x.isConstant() && x.m_center == 0; }",
          "friend bool IsExactlyZero(const ReducedAffine& x) { return x.m_center == 0 && x.m_error == 0; }",
          "a form 0 + a eps_u + b eps_v counts as an exactly zero derivative"),
    Fault("interval-div-zero-end-bounded", "vm/numbers/interval.cpp",
          "if (a.m_lo > 0) return Interval::Extended(DivDown(a.m_lo, b.m_hi), kInfinity);",
          "if (a.m_lo > 0) return Interval(DivDown(a.m_lo, b.m_hi), kMaxFinite);",
          "a quotient by [0, hi] is bounded, not partial: sqrt's factor 0.5/sqrt(a) where a reaches 0"),
    Fault("interval-join-low-end", "vm/numbers/interval.h",
          "return Extended(std::fmin(a.m_lo, b.m_lo), std::fmax(a.m_hi, b.m_hi));",
          "return Extended(std::fmax(a.m_lo, b.m_lo), std::fmax(a.m_hi, b.m_hi));",
          "the hull (Join of undecided derivatives) takes the larger low end"),
    Fault("reduced-join-quarter-spread", "vm/numbers/reduced_affine.cpp",
          "const double error = (std::fmax(a.error(), b.error()) + 0.5 * spread +",
          "const double error = (std::fmax(a.error(), b.error()) + 0.25 * spread +",
          "Join's error holds half the distance between the operands"),
    Fault("reduced-join-drop-rounding", "vm/numbers/reduced_affine.cpp",
          "const double error = (std::fmax(a.error(), b.error()) + 0.5 * spread +\n"
          "                          (std::fabs(c) + std::fabs(u) + std::fabs(v) + spread) * kEpsilon) *",
          "const double error = (std::fmax(a.error(), b.error()) + 0.5 * spread) *",
          "Join's error leaves out the rounding of its midpoint form"),
    Fault("reduced-scale-error-unscaled", "vm/numbers/reduced_affine.h",
          "const double scaledError = std::fabs(c) * x.m_error * (1 + kEpsilon);",
          "const double scaledError = x.m_error * (1 + kEpsilon);",
          "x * c keeps x's error unscaled (a chain-rule factor times a derivative)"),

    Fault("product-remainder-drop-rounding", "vm/numbers/rounding.h",
          "return (quad + linear + rounding) * kSumSlack + kUnderflowSlack;",
          "return (quad + linear + 0 * rounding) * kSumSlack + kUnderflowSlack;",
          "an affine product's error leaves out the rounding of its terms (the product rule's products)"),
    Fault("reduced-fit-drop-rounding", "vm/numbers/reduced_affine.cpp",
          "const double delta = (delta0 + std::fabs(alpha) * x.m_error + absSum * kEpsilon) * kSumSlack + kUnderflowSlack;",
          "const double delta = (delta0 + std::fabs(alpha) * x.m_error + absSum * 0) * kSumSlack + kUnderflowSlack;",
          "a reduced affine fit (every chain-rule factor: exp, sqrt, 1/x...) leaves out the rounding of its form",
          equivalent="redundant slack: every fit's bounds on f(t) - alpha t already hold more than the "
          "form's rounding (4 ulps of glibc slack, or directed roundings of 1/t and sqrt, at each end): "
          "in binary128, 0 of 11 million points of regions 1 to 1e-16 of their centre wide fall outside "
          "the form without the term (1/x, sqrt, exp, log, sin, tan, atan, asin and floor fits)"),
    Fault("sign-fit-one-side", "vm/numbers/affine_fit.cpp",
          "return AffineFit::Line(0.0, range.lo() < 0 ? -1.0 : 0.0, range.hi() > 0 ? 1.0 : 0.0);",
          "return AffineFit::Line(0.0, 0.0, range.hi() > 0 ? 1.0 : 0.0);",
          "the affine sign of a range straddling 0 is [0, 1]: abs's derivative factor loses its negative side"),

    # --- Noise --------------------------------------------------------------------------------------
    Fault("noise-fallback-gradient-one-sign", "vm/numbers/noise.h",
          "raw = CellPolynomial(t, dims, [&](int, int) { return Join(T(-bound), T(bound)); });",
          "raw = CellPolynomial(t, dims, [&](int, int) { return T(bound); });",
          "the cell-independent bound takes every gradient component as +G, not [-G, G]"),
    Fault("noise-fallback-component-bound", "vm/numbers/noise.cpp",
          "{2, 8, kGradients2, kC}",
          "{2, 8, kGradients2, kS}",
          "2-D noise's largest gradient component taken as sin 22.5 deg instead of cos"),
    Fault("noise-cells-last-only", "vm/numbers/noise.h",
          "raw = first ? v : Join(raw, v);",
          "raw = v;",
          "a region over several cells takes the last cell's bound, not the join"),
    Fault("dual-spread-derivatives-zero", "vm/numbers/number.h",
          "const B unknown = Spread<B>::Of(Interval::Unbounded());",
          "const B unknown = Spread<B>::Of(Interval(0.0));",
          "a spread Dual (noise of an unbounded or overflowing operand) gets derivatives 0, not unknown"),

    # --- Texture ------------------------------------------------------------------------------------
    Fault("texture-slope-term-one-sided", "vm/texture_lookup.h",
          "return SpreadOf<B>(Interval::Extended(-slope, slope)) * d;",
          "return SpreadOf<B>(Interval::Extended(0.0, slope)) * d;",
          "a lookup's derivative bound takes the slope as [0, S], not [-S, S]"),
    Fault("texture-dual-slopes-swapped", "vm/texture_lookup.h",
          "return {value, SlopeTerm(sSlope, s.du) + SlopeTerm(tSlope, t.du),",
          "return {value, SlopeTerm(sSlope, s.du) + SlopeTerm(sSlope, t.du),",
          "the u-derivative bound of a lookup multiplies t's movement by the s slope"),
    Fault("texture-quad-movement-first-corner", "vm/texture_lookup.h",
          "for (int i = 1; i < 4; ++i) m = Join(m, u ? c[2 * i + k].du : c[2 * i + k].dv);",
          "",
          "a four-corner lookup's derivative bound takes the first corner's movement, not the join of all four"),
    Fault("texture-slope-no-kink-texel", "texture/lookup.cpp",
          "k.map->RangeOfTexels(x.lo - 1, x.hi + 1, y.lo - 1, y.hi + 1, k.c, k.swrap, k.twrap);",
          "k.map->RangeOfTexels(x.lo, x.hi, y.lo, y.hi, k.c, k.swrap, k.twrap);",
          "SlopeOver leaves out the texels past the region's (read by one-sided derivatives at a kink)"),
    Fault("texture-slope-catrom-factor", "texture/lookup.cpp",
          "const double factor = k.catrom ? kCatromSlope : 1.0;",
          "const double factor = 1.0;",
          "SlopeOver drops Catmull-Rom's factor 2"),
    Fault("texture-slope-axes-swapped", "texture/lookup.cpp",
          "*sSlope = spread * factor * k.width;",
          "*sSlope = spread * factor * k.height;",
          "SlopeOver scales the s slope by the map's height"),
    Fault("texture-slope-drop-weight-rounding", "texture/lookup.cpp",
          "const double spread = (r.hi - r.lo) * (1 + kSlack) + std::max(std::fabs(r.lo), std::fabs(r.hi)) * kSlack + kTiny;",
          "const double spread = (r.hi - r.lo) * (1 + kSlack) + kTiny;",
          "SlopeOver leaves out the rounding of the derivative weights (a slope over constant texels)"),
]


WIDTH = max(len(f.name) for f in FAULTS)

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


def check_faults(root, faults):
    """Every fault's old text occurs exactly once in its file, and differs from its new text."""
    names = set()
    problems = []
    for f in faults:
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
    if problems:
        raise Error("planted faults that no longer match the tree (fix FAULTS):\n  " + "\n  ".join(problems))


# ---------------------------------------------------------------------------------------------
# The scratch trees.

SUBDIR = "_mutate_derivatives"
CMAKE_HOOK = f"\n# Added by tools/mutate_derivatives.py in its scratch copy only.\nadd_subdirectory({SUBDIR})\n"


def small_target_cmake():
    sources = " ".join("${PROJECT_SOURCE_DIR}/" + s for s in ["tests/main.cpp"] + TEST_SOURCES)
    return f"""# The derivative tests alone (tools/mutate_derivatives.py), with the suite's flags (tests/CMakeLists.txt).
find_package(Catch2 2 REQUIRED)
add_executable({TARGET} {sources})
target_compile_options({TARGET} PRIVATE -O1)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options({TARGET} PRIVATE -Wno-array-bounds -Wno-stringop-overflow -Wno-stringop-overread)
endif()
set_source_files_properties(${{PROJECT_SOURCE_DIR}}/tests/main.cpp PROPERTIES COMPILE_OPTIONS
                            "-O0;-g0;-Wno-maybe-uninitialized")
target_include_directories({TARGET} PRIVATE ${{PROJECT_SOURCE_DIR}})
target_link_libraries({TARGET} PRIVATE affray_vm affray_texture Catch2::Catch2)
target_compile_definitions({TARGET} PRIVATE AFFRAY_SOURCE_DIR="${{PROJECT_SOURCE_DIR}}")
"""


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
    ignored ones), copying only what differs, plus the small target."""
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
    put(os.path.join(src, SUBDIR, "CMakeLists.txt"), small_target_cmake())


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


def build(src, build_dir, log):
    if not os.path.isfile(os.path.join(build_dir, "build.ninja")):
        status = run_logged(["cmake", "-S", src, "-B", build_dir, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                                    "-DAFFRAY_TESTS=OFF", "-DAFFRAY_BENCH=OFF"], log)
        if status != 0:
            return False
    return run_logged(["cmake", "--build", build_dir, "--target", TARGET, "--", "-j1"], log) == 0


# ---------------------------------------------------------------------------------------------
# Running the tests.


@dataclasses.dataclass
class Outcome:
    status: str  # "killed", "survived", "build failed", "error"
    by: list = dataclasses.field(default_factory=list)  # the failing test cases, or how the run ended
    build_s: float = 0.0
    test_s: float = 0.0


def run_tests(build_dir, spec, log, timeout):
    """Runs the small binary on spec: (passed, the failing test cases or how the run ended)."""
    binary = os.path.join(build_dir, SUBDIR, TARGET)
    with tempfile.NamedTemporaryFile(suffix=".xml", delete=False) as tmp:
        report = tmp.name
    try:
        status = run_logged([binary, spec, "--reporter", "xml", "--out", report], log, timeout=timeout)
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

    def prepare(self):
        sync_tree(ROOT, self.src)
        if os.path.exists(self.log):
            os.remove(self.log)
        return build(self.src, self.build, self.log)

    def run(self, fault, spec, timeout):
        path = os.path.join(self.src, fault.file)
        original = read(path)
        if original.count(fault.old) != 1:
            return Outcome("error", ["the old text does not occur exactly once in the scratch copy"])
        with open(self.log, "a") as out:
            out.write(f"\n===== {fault.name}\n")
        try:
            write(path, original.replace(fault.old, fault.new))
            t0 = time.monotonic()
            built = build(self.src, self.build, self.log)
            t1 = time.monotonic()
            if not built:
                return Outcome("build failed", [f"see {self.log}"], t1 - t0)
            passed, by = run_tests(self.build, spec, self.log, timeout)
            t2 = time.monotonic()
            return Outcome("survived" if passed else "killed", by, t1 - t0, t2 - t1)
        finally:
            write(path, original)  # the scratch copy only; the next build redoes its dependents


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--list", action="store_true", help="list the faults and exit")
    parser.add_argument("--only", metavar="NAME[,NAME...]", help="run only these faults")
    parser.add_argument("--jobs", type=int, default=1, help="mutants built and tested at once (one scratch tree each)")
    parser.add_argument("--scratch", default="/tmp/mutate-derivatives", help="scratch directory")
    parser.add_argument("--tests", default=TEST_SPEC, help=f"Catch2 test spec (default {TEST_SPEC})")
    args = parser.parse_args()

    def interrupted(signum, frame):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, interrupted)

    try:
        check_faults(ROOT, FAULTS)
    except Error as e:
        print(f"mutate_derivatives: {e}", file=sys.stderr)
        return 2
    faults = FAULTS
    if args.only:
        wanted = args.only.split(",")
        unknown = [n for n in wanted if n not in {f.name for f in FAULTS}]
        if unknown:
            print(f"mutate_derivatives: no fault named {', '.join(unknown)} (--list lists them)", file=sys.stderr)
            return 2
        faults = [f for f in FAULTS if f.name in wanted]
    if args.list:
        for f in faults:
            tag = "  (equivalent: not counted)" if f.equivalent else ""
            print(f"{f.name:{WIDTH}} {f.file}: {f.what}{tag}")
        return 0

    jobs = max(1, min(args.jobs, len(faults)))
    os.makedirs(args.scratch, exist_ok=True)
    workers = [Worker(args.scratch, i) for i in range(jobs)]
    print(f"Baseline: {len(workers)} scratch tree(s) in {args.scratch}, building {TARGET} ...", flush=True)
    t0 = time.monotonic()
    for w in workers:
        if not w.prepare():
            print(f"mutate_derivatives: the baseline does not build (see {w.log})", file=sys.stderr)
            return 2
    build_s = time.monotonic() - t0
    t1 = time.monotonic()
    passed, by = run_tests(workers[0].build, args.tests, workers[0].log, timeout=3600)
    base_s = time.monotonic() - t1
    if not passed:
        print(f"mutate_derivatives: the baseline fails its tests ({', '.join(by)}; see {workers[0].log})",
              file=sys.stderr)
        return 2
    print(f"Baseline built in {build_s:.0f} s, tests pass in {base_s:.0f} s.", flush=True)
    timeout = max(60.0, 5 * base_s)

    results = {}
    lock = threading.Lock()
    free = list(workers)

    def one(fault):
        with lock:
            w = free.pop()
        try:
            outcome = w.run(fault, args.tests, timeout) if not STOP.is_set() else Outcome("error", ["interrupted"])
        finally:
            with lock:
                free.append(w)
        with lock:
            results[fault.name] = outcome
            print(f"  {fault.name:{WIDTH}} {outcome.status:12} build {outcome.build_s:4.0f} s, tests {outcome.test_s:4.0f} s, "
                  f"{len(outcome.by)} failing", flush=True)
        return outcome

    t2 = time.monotonic()
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=jobs)
    try:
        for future in [pool.submit(one, f) for f in faults]:
            future.result()
    except KeyboardInterrupt:
        STOP.set()
        kill_active()
        pool.shutdown(wait=True, cancel_futures=True)
        print("mutate_derivatives: interrupted (the scratch copies are restored; the repository was never touched)",
              file=sys.stderr)
        return 2
    pool.shutdown()
    total_s = time.monotonic() - t2

    print()
    print(f"{'fault':{WIDTH}} {'file':30} {'result':10} failing test cases")
    for f in faults:
        o = results[f.name]
        status = o.status + (" (equivalent)" if f.equivalent else "")
        print(f"{f.name:{WIDTH}} {f.file:30} {status:10} {'; '.join(short_name(n) for n in o.by)}")
    counted = [f for f in faults if not f.equivalent]
    killed = [f for f in counted if results[f.name].status == "killed"]
    survived = [f for f in counted if results[f.name].status == "survived"]
    errors = [f for f in faults if results[f.name].status in ("build failed", "error")]
    rate = 100.0 * len(killed) / len(counted) if counted else 100.0
    print()
    print(f"Kill rate: {len(killed)}/{len(counted)} = {rate:.1f} % of the counted faults "
          f"({len(faults) - len(counted)} equivalent, not counted); {total_s / 60:.1f} min for "
          f"{len(faults)} mutants, {total_s / max(1, len(faults)):.0f} s each on average, {jobs} job(s).")
    if errors:
        print("Errors: " + ", ".join(f.name for f in errors), file=sys.stderr)
        return 2
    return 1 if survived else 0


if __name__ == "__main__":
    sys.exit(main())
