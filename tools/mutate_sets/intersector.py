"""The intersector set: planted faults in the renderer's intersector (renderer/intersect.cpp, the
region measures of renderer/measure.h, the split rule of renderer/bound_tree.cpp and the certified
roots of renderer/newton.cpp): region culling, the nearest-first order, splitting, the tolerance
and leaf tests, the ray-box and ray-group tests, the parallelogram narrowing and the certified
error of a hit.

Issue 33, item 3. The binary holds the renderer's intersection tests (intersect, bound tree and
ray groups, measures, Newton, stiff surfaces, BVH, shadows, facing) and the whole-render tests of
render_test.cpp, and links the renderer and what it needs (not the CLI). A mutant rebuilds one or
a few renderer sources and relinks.
"""

from mutate_sets import Fault, FaultSet

FAULTS = [
    # --- renderer/intersect.cpp: the walk --------------------------------------------------------------
    Fault("walk-farthest-first", "renderer/intersect.cpp",
          "for (size_t j = i; j > first && m_stack[j - 1].tLo < m_stack[j].tLo; --j)",
          "for (size_t j = i; j > first && m_stack[j - 1].tLo > m_stack[j].tLo; --j)",
          "children are walked farthest first, not nearest first"),
    Fault("walk-keeps-regions-past-the-hit", "renderer/intersect.cpp",
          "if (r.tLo > best) continue;  // a nearer hit was found since this region was measured",
          "",
          "a region beyond the nearest hit found so far is still walked (and may replace it)"),
    Fault("leaf-tolerance-doubled", "renderer/intersect.cpp",
          "bool small = r.size <= tolerance.At(r.tLo);",
          "bool small = r.size <= 2 * tolerance.At(r.tLo);",
          "the leaf test accepts regions twice the tolerance"),
    Fault("leaf-depth-limit-one-axis", "renderer/intersect.cpp",
          "const bool atLimit = r.levelU >= maxDepth && r.levelV >= maxDepth;",
          "const bool atLimit = r.levelU >= maxDepth || r.levelV >= maxDepth;",
          "a region at the depth limit along one parameter counts as a leaf"),
    Fault("leaf-error-half-size", "renderer/intersect.cpp",
          "error = r.size;\n            } else {",
          "error = 0.5 * r.size;\n            } else {",
          "a leaf hit's certified error is half the region's size"),
    Fault("leaf-hit-ignores-trim", "renderer/intersect.cpp",
          "if (!surface.KeptP(r.hu, r.hv)) continue;",
          "",
          "a leaf hit in a trimmed (or clipped) part of the surface is kept"),
    Fault("leaf-unproved-size-kept", "renderer/intersect.cpp",
          "if (small && r.size > kUnprovedLeaf * tolerance.At(r.tLo)) small = false;",
          "",
          "a region Newton could not certify is a leaf at the full tolerance"),
    Fault("newton-accepts-root-before-tmin", "renderer/intersect.cpp",
          "const bool proved = n.roots == Roots::One && n.tLo >= tMin;",
          "const bool proved = n.roots == Roots::One;",
          "a certified root whose t may lie before tMin is taken"),
    Fault("newton-miss-straddling-tmin", "renderer/intersect.cpp",
          "(n.roots == Roots::One && n.tHi < tMin)",
          "(n.roots == Roots::One && n.tLo < tMin)",
          "a certified root whose t range straddles tMin is dropped as a miss"),
    Fault("budget-picks-farthest", "renderer/intersect.cpp",
          "r.tLo <= best && (!nearest || r.tLo < nearest->tLo) && surface.KeptP(r.hu, r.hv))",
          "r.tLo <= best && (!nearest || r.tLo > nearest->tLo) && surface.KeptP(r.hu, r.hv))",
          "on an exhausted budget the farthest pending region is the hit"),
    Fault("child-reach-cull-wrong-end", "renderer/intersect.cpp",
          "if (c.u1 < r.ru0 || c.u0 > r.ru1 || c.v1 < r.rv0 || c.v0 > r.rv1) continue;",
          "if (c.u1 < r.ru0 || c.u0 > r.ru0 || c.v1 < r.rv0 || c.v0 > r.rv1) continue;",
          "a child is culled when it starts past the reachable part's low end, not its high end"),

    # --- renderer/intersect.cpp: Test (culling, ray-box, parallelogram) -----------------------------------
    Fault("box-range-no-swap", "renderer/intersect.cpp",
          "if (t0 > t1) std::swap(t0, t1);",
          "",
          "the ray-box slab test does not order the slab's ends (rays along -x, -y or -z)"),
    Fault("box-range-no-slack", "renderer/intersect.cpp",
          "const double slack = 2 * kUlp * (std::fabs(b.lo[i]) + std::fabs(b.hi[i]) + std::fabs(m_origin[i]));",
          "const double slack = 0;",
          "the ray-box test leaves out the rounding of the box's offsets",
          equivalent="redundant slack: a difference of two doubles rounds by half an ulp of itself, not "
          "of its operands, so with the reciprocal and the product each slab end is within 3 ulps of "
          "its exact value and the 4-ulp widening after it holds it (a direction component so small "
          "that its reciprocal overflows gives infinite or NaN ends, which cull nothing either way): "
          "without the slack no region the ray can meet is culled; it only keeps fewer regions the "
          "ray misses by an ulp of the coordinates, so a result can move by rounding at most"),
    Fault("box-range-parallel-ray-inverted", "renderer/intersect.cpp",
          "if (c0 - slack > 0 || c1 + slack < 0) return false;",
          "if (c0 - slack < 0 && c1 + slack > 0) return false;",
          "a ray parallel to a slab is culled when it lies inside the slab, not outside"),
    Fault("cull-t-range-straddling-tmin", "renderer/intersect.cpp",
          "if (lo > hi || lo > best) return false;",
          "if (rt.lo < lo || lo > hi || lo > best) return false;",
          "a region reaching before tMin is culled though it reaches past it too"),
    Fault("parallelogram-drops-third-symbol", "renderer/intersect.cpp",
          "const double R1 = std::fabs(d1.w) + d1.rad, R2 = std::fabs(d2.w) + d2.rad;",
          "const double R1 = d1.rad, R2 = d2.rad;",
          "the parallelogram narrowing leaves out the bound's third symbol (its spread besides u and v)"),
    Fault("parallelogram-v-solution-sign", "renderer/intersect.cpp",
          "sv = -d2.c * d1.u + d1.c * d2.u;",
          "sv = d2.c * d1.u - d1.c * d2.u;",
          "Cramer's rule for the ray's v in the parallelogram has the wrong sign"),
    # (The bound on the solve's rounding is set to 0 rather than left out of du: an unused
    # variable does not build with -Werror.) It survives, not shown equivalent: errU is at most
    # about a quarter of the kSlack part of du (eight times the measures' own rounding) wherever
    # the solution lies within a few region widths; farther out it could only cut a region where
    # the parallelogram's edge is within rounding of the region's edge (README, planted faults).
    Fault("parallelogram-drops-rounding", "renderer/intersect.cpp",
          "const double errU =\n            2 * (2 * kUlp",
          "const double errU =\n            0 * (2 * kUlp",
          "the narrowing along u leaves out the rounding of the solve"),
    Fault("parallelogram-reach-half-radius", "renderer/intersect.cpp",
          "e.ru0 = std::max(e.u0, pu + pr * (cu - ru) - su);",
          "e.ru0 = std::max(e.u0, pu + pr * (cu - 0.5 * ru) - su);",
          "the reachable part's low u end is half a radius from its centre"),
    Fault("edge-separates-drops-radius", "renderer/intersect.cpp",
          "const double rad = a2 * d1.rad + a1 * d2.rad;",
          "const double rad = 0;",
          "the edge-on separation test leaves out the bounds' radius"),
    Fault("children-missed-sides-swapped", "renderer/intersect.cpp",
          "if (highU)\n                uLo = std::max(uLo, -padU);",
          "if (!highU)\n                uLo = std::max(uLo, -padU);",
          "the test of which children a ray misses gives each u half the other's range"),
    Fault("hit-parameter-far-side", "renderer/intersect.cpp",
          "hitU = t.u > 0 ? -1 : t.u < 0 ? 1 : 0;",
          "hitU = t.u > 0 ? 1 : t.u < 0 ? -1 : 0;",
          "an un-narrowed region's hit parameter is taken at its far side in u"),

    # --- ray groups -------------------------------------------------------------------------------
    Fault("group-normal-outward", "renderer/intersect.cpp",
          "if (glm::dot(n, inside) < glm::dot(n, a.origin)) n = -n;",
          "if (glm::dot(n, inside) > glm::dot(n, a.origin)) n = -n;",
          "a ray group's side planes face outward"),
    Fault("group-box-lowest-corner", "renderer/intersect.cpp",
          "boxHi += n[i] > 0 ? n[i] * b.hi[i] : n[i] * b.lo[i];",
          "boxHi += n[i] > 0 ? n[i] * b.lo[i] : n[i] * b.hi[i];",
          "a bound is outside a ray group when its box's lowest corner is, not its highest"),

    # --- renderer/measure.h -----------------------------------------------------------------------
    Fault("measure-excludes-touching-zero", "renderer/measure.h",
          "bool excludesZero() const { return lo > 0 || hi < 0; }",
          "bool excludesZero() const { return lo >= 0 || hi <= 0; }",
          "a range touching 0 (a ray grazing the bound) counts as missing it"),
    Fault("measure-over-drops-w", "renderer/measure.h",
          "double rad = std::fabs(m.u) * ru + std::fabs(m.v) * rv + std::fabs(m.w) + m.rad;",
          "double rad = std::fabs(m.u) * ru + std::fabs(m.v) * rv + m.rad;",
          "a measure over a sub-box leaves out the third symbol"),

    # --- renderer/bound_tree.cpp: the split rule ---------------------------------------------------------
    Fault("split-stretched-axis-swapped", "renderer/bound_tree.cpp",
          "if (a2 > 4 * b2) return kSplitU;",
          "if (a2 > 4 * b2) return kSplitV;",
          "a region stretched along u is split across v"),
    Fault("split-past-depth-limit", "renderer/bound_tree.cpp",
          "if (levelU >= maxDepth) return kSplitV;",
          "if (levelU >= maxDepth) return kSplitBoth;",
          "a region at the depth limit in u is still split in u"),

    # --- renderer/newton.cpp: certified roots ------------------------------------------------------------
    Fault("newton-one-root-without-strict-inclusion", "renderer/newton.cpp",
          "inside = inside && K.x[i].lo() > X.x[i].lo() && K.x[i].hi() < X.x[i].hi();",
          "inside = inside && K.x[i].lo() > X.x[i].lo();",
          "Krawczyk's test proves one root when the image is inside the box at one end only"),
    Fault("newton-none-when-not-inside", "renderer/newton.cpp",
          "if (K.x[i].hi() < X.x[i].lo() || K.x[i].lo() > X.x[i].hi()) return Roots::None;",
          "if (K.x[i].hi() < X.x[i].hi() || K.x[i].lo() > X.x[i].hi()) return Roots::None;",
          "Krawczyk's test says no root when the image ends below the box's high end"),
    Fault("newton-identity-off-diagonal", "renderer/newton.cpp",
          "m_m[i][j] = Interval(i == j ? 1.0 : 0.0) - (Y[i][0] * J[0][j] + Y[i][1] * J[1][j]);",
          "m_m[i][j] = Interval(1.0) - (Y[i][0] * J[0][j] + Y[i][1] * J[1][j]);",
          "the Krawczyk map's I - YJ takes 1 off the diagonal too"),
    Fault("newton-error-drops-along-ray", "renderer/newton.cpp",
          "const double along = std::max(hit.t - hit.tLo, hit.tHi - hit.t);",
          "const double along = 0;",
          "a certified hit's error leaves out its spread along the ray"),
]

SET = FaultSet(
    name="intersector",
    what="the renderer's intersector: culling, order, splitting, tolerance and leaf tests, ray-box tests",
    test_sources=[
        "tests/renderer/intersect_test.cpp",
        "tests/renderer/measure_test.cpp",
        "tests/renderer/bound_tree_test.cpp",
        "tests/renderer/newton_test.cpp",
        "tests/renderer/stiff_test.cpp",
        "tests/renderer/stiff_sphere_test.cpp",
        "tests/renderer/bvh_test.cpp",
        "tests/renderer/shadow_test.cpp",
        "tests/renderer/facing_test.cpp",
        "tests/renderer/render_test.cpp",
    ],
    test_spec="",
    libraries=["affray_rib", "affray_renderer", "affray_compiler", "affray_vm", "affray_texture", "affray_lang",
               "affray_image", "OpenEXR::OpenEXR", "ZLIB::ZLIB"],
    faults=FAULTS,
)
