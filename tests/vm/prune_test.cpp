// tests/vm/prune_test.cpp: tape pruning (vm/prune.*) and the interpreter's recording of what a
// bound evaluation decided. The contract: over any sub-region of the region the decisions were
// recorded over, the pruned program verifies, gives the full program's scalar results bit for
// bit, and its affine and interval bounds contain them. Checked on every shader in shaders/,
// pruned again and again as the intersector does, then on small programs whose pruning is known
// exactly, and last in the intersector (renderer/intersect.cpp), which must find the same hits. AFFRAY_SAMPLES=N raises the region count; AFFRAY_VERBOSE=1 prints instruction counts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "renderer/intersect.h"
#include "tests/test_random.h"
#include "tests/test_util.h"
#include "vm/prune.h"
#include "vm/verify.h"

using namespace affray;
using test::Rng;

namespace {

struct Region {
    double u0, u1, v0, v1;
};

/// Runs `program` over `r` in N (its dual if it takes derivatives) with recording on.
template <class N>
vm::Decisions Record(const vm::Program& program, const Region& r) {
    auto run = [&](auto interp) {
        interp.SetRecording(true);
        renderer::EvaluateOnPatch(interp, renderer::BilinearPatch::UnitSquare(), r.u0, r.u1, r.v0, r.v1,
                                  glm::dvec3(0.0), *program.findOutput("P"));
        return interp.decisions();
    };
    if (program.usesDerivatives()) return run(vm::Interpreter<vm::Dual<N>>(program));
    return run(vm::Interpreter<N>(program));
}

template <class N>
std::array<vm::Interval, 3> Bound(const vm::Program& program, const Region& r, const char* output) {
    std::array<vm::Interval, 3> out;
    if (program.usesDerivatives()) {
        auto p = test::EvalOnSquare<vm::Dual<N>>(program, r.u0, r.u1, r.v0, r.v1, output);
        for (int i = 0; i < 3; ++i) out[i] = RangeOf(p[i].v);
    } else {
        auto p = test::EvalOnSquare<N>(program, r.u0, r.u1, r.v0, r.v1, output);
        for (int i = 0; i < 3; ++i) out[i] = RangeOf(p[i]);
    }
    return out;
}

/// A random sub-region of `r`, `shrink` times narrower or so.
Region SubRegion(Rng& rng, const Region& r, double shrink) {
    auto side = [&](double lo, double hi, double* a, double* b) {
        const double w = (hi - lo) * shrink * rng.uniform(0.5, 1.0);
        *a = lo + (hi - lo - w) * rng.uniform(0, 1);
        *b = std::min(hi, *a + w);
    };
    Region s;
    side(r.u0, r.u1, &s.u0, &s.u1);
    side(r.v0, r.v1, &s.v0, &s.v1);
    return s;
}

/// A point of `r`: a corner, the centre, or uniform.
std::array<double, 2> PointIn(Rng& rng, const Region& r, int k) {
    const double fu = k < 4 ? (k & 1) : k == 4 ? 0.5 : rng.uniform(0, 1);
    const double fv = k < 4 ? (k >> 1) : k == 4 ? 0.5 : rng.uniform(0, 1);
    return {std::min(r.u1, r.u0 + fu * (r.u1 - r.u0)), std::min(r.v1, r.v0 + fv * (r.v1 - r.v0))};
}

bool SameBits(const glm::dvec3& a, const glm::dvec3& b) {
    for (int i = 0; i < 3; ++i)
        if (std::bit_cast<uint64_t>(a[i]) != std::bit_cast<uint64_t>(b[i])) return false;
    return true;
}

std::string Describe(const Region& r) {
    return "[" + std::to_string(r.u0) + "," + std::to_string(r.u1) + "]x[" + std::to_string(r.v0) + "," +
           std::to_string(r.v1) + "]";
}

/// Prunes `program` for `region` (decisions recorded in N), checks the contract on sub-regions
/// and points of it, and returns the pruned program.
template <class N>
vm::Program PruneAndCheck(const std::string& name, const vm::Program& full, const vm::Program& program,
                          const Region& region, const std::vector<const char*>& outputs, Rng& rng, test::Tally& tally) {
    vm::Program pruned = vm::Prune(program, Record<N>(program, region));
    std::string error;
    ++tally.samples;
    if (!vm::Verify(pruned, &error)) tally.fail(name + " " + Describe(region) + ": pruned program: " + error);
    if (pruned.code.size() > program.code.size()) tally.fail(name + ": pruning made the program longer");
    if (tally.failures) return program;
    for (int s = 0; s < 3; ++s) {
        const Region sub = s == 0 ? region : SubRegion(rng, region, s == 1 ? 0.5 : 0.01);
        for (const char* output : outputs) {
            const auto affine = Bound<vm::Affine>(pruned, sub, output);
            const auto interval = Bound<vm::Interval>(pruned, sub, output);
            for (int k = 0; k < 7; ++k) {
                const auto [u, v] = PointIn(rng, sub, k);
                const glm::dvec3 want = test::PointOnSquare(full, u, v, output);
                const glm::dvec3 got = test::PointOnSquare(pruned, u, v, output);
                if (!SameBits(want, got))
                    tally.fail(name + " " + output + " at (" + std::to_string(u) + ", " + std::to_string(v) +
                               "): pruned for " + Describe(region) + " gives another result");
                for (int i = 0; i < 3; ++i)
                    if (!affine[i].contains(got[i]) || !interval[i].contains(got[i]))
                        tally.fail(name + " " + output + ": the pruned bound over " + Describe(sub) +
                                   " misses the scalar result");
            }
        }
    }
    return pruned;
}

/// From the whole domain down, each level a random quarter-ish of the last, pruning the pruned
/// program again at each level (as the intersector does); checks each against the full program.
template <class N>
void CheckShader(const std::string& name, const vm::Program& full, const std::vector<const char*>& outputs, int chains,
                 uint64_t seed) {
    Rng rng(seed);
    test::Tally tally;
    std::vector<std::pair<size_t, size_t>> sizes;  // (depth, instructions) for the verbose report
    for (int c = 0; c < chains && tally.failures == 0; ++c) {
        Region region{0, 1, 0, 1};
        vm::Program program = full;
        for (int depth = 0; depth <= 14 && tally.failures == 0; depth += 2) {
            program = PruneAndCheck<N>(name, full, program, region, outputs, rng, tally);
            sizes.emplace_back(depth, program.code.size());
            region = SubRegion(rng, region, 0.25);
        }
    }
    INFO(tally.first.str());
    CHECK(tally.failures == 0);
    if (std::getenv("AFFRAY_VERBOSE")) {
        std::printf("%-40s %s %zu instructions; pruned by depth:", name.c_str(), vm::NumberTraits<N>::kName,
                    full.code.size());
        for (size_t depth = 0; depth <= 14; depth += 2) {
            double sum = 0;
            int n = 0;
            for (auto [d, size] : sizes)
                if (d == depth) sum += static_cast<double>(size), ++n;
            if (n) std::printf(" %zu:%.0f", depth, sum / n);
        }
        std::printf("\n");
    }
}

vm::Instr I(vm::Op op, uint16_t a, uint16_t b = 0, uint16_t c = 0) { return vm::Instr{op, 0, a, b, c}; }

/// A program over the globals u (r0) and v (r1) with output P = (u, v, R[z]).
vm::Program Hand(std::vector<vm::Instr> code, std::vector<double> constants, int registers, uint16_t z) {
    vm::Program p;
    p.code = std::move(code);
    p.constants = std::move(constants);
    p.registerCount = registers;
    p.globalRegisters[static_cast<int>(vm::Global::u)] = 0;
    p.globalRegisters[static_cast<int>(vm::Global::v)] = 1;
    p.outputs.push_back({"P", 3, {0, 1, z}});
    std::string error;
    REQUIRE(vm::Verify(p, &error));
    return p;
}

std::vector<vm::Op> Ops(const vm::Program& p) {
    std::vector<vm::Op> ops;
    for (const vm::Instr& in : p.code) ops.push_back(in.op);
    return ops;
}

vm::Program PruneFor(const vm::Program& p, const Region& r) {
    vm::Program pruned = vm::Prune(p, Record<vm::Affine>(p, r));
    std::string error;
    INFO(error);
    REQUIRE(vm::Verify(pruned, &error));
    Rng rng(1);
    for (int k = 0; k < 9; ++k) {
        const auto [u, v] = PointIn(rng, r, k);
        REQUIRE(SameBits(test::PointOnSquare(p, u, v), test::PointOnSquare(pruned, u, v)));
    }
    return pruned;
}

}  // namespace

TEST_CASE("pruned shader programs agree with the full ones bit for bit", "[vm][prune]") {
    const int chains = test::Samples(6);
    uint64_t seed = 11;
    for (const std::string& path : test::AllShaders()) {
        compiler::CompileResult r = compiler::CompileFile(path);
        INFO(path << "\n" << r.diagnostics);
        REQUIRE(r.ok());
        CheckShader<vm::Affine>(path, r.shader->bound, {"P"}, chains, ++seed);
        CheckShader<vm::Interval>(path, r.shader->bound, {"P"}, chains / 2, ++seed);
        // The shade program takes derivatives: recorded in Dual<Affine>, where choices are used
        // but constants are not.
        CheckShader<vm::Affine>(path + " (shade)", r.shader->shade, {"P", "N"}, 1, ++seed);
    }
}

TEST_CASE("a decided select drops its dead arm and its condition", "[vm][prune]") {
    // z = u < 0.5 ? sin(v) : v * 2
    const vm::Program p = Hand({I(vm::Op::LtRK, 2, 0, 0), I(vm::Op::Sin, 3, 1), I(vm::Op::MulRK, 4, 1, 1),
                                I(vm::Op::Select, 2, 2, 3), I(vm::Op::Ext, 4)},
                               {0.5, 2.0}, 5, 2);
    const vm::Program left = PruneFor(p, {0.1, 0.2, 0.3, 0.9});
    CHECK(Ops(left) == std::vector<vm::Op>{vm::Op::Sin});
    const vm::Program right = PruneFor(p, {0.6, 0.9, 0.3, 0.9});
    CHECK(Ops(right) == std::vector<vm::Op>{vm::Op::MulRK});
    CHECK(right.constants == std::vector<double>{2.0});
    // Straddling the condition: nothing decided, nothing dropped.
    const vm::Program both = PruneFor(p, {0.4, 0.6, 0.3, 0.9});
    CHECK(Ops(both) == Ops(p));
    // Registers are compacted: u, v, then what the code needs.
    CHECK(left.registerCount == 3);
}

TEST_CASE("a min or max of strictly ordered operands gives that operand", "[vm][prune]") {
    // z = max(min(u, v), 0.75): over u in [0, 0.1], v in [0.5, 0.6], min is u and max is 0.75.
    const vm::Program p = Hand({I(vm::Op::MinRR, 2, 0, 1), I(vm::Op::MaxRK, 2, 2, 0)}, {0.75}, 3, 2);
    vm::Decisions d = Record<vm::Affine>(p, {0, 0.1, 0.5, 0.6});
    CHECK(d.operandAt(0) == 1);
    double k = 0;
    CHECK(d.constantAt(1, &k));
    CHECK(k == 0.75);
    CHECK(Ops(PruneFor(p, {0, 0.1, 0.5, 0.6})) == std::vector<vm::Op>{vm::Op::LoadK});
    // max(min(u, v), 0.75) with u in [0.8, 0.9] and v in [0.5, 0.6]: min is v, max is 0.75 again.
    // With v in [0.8, 0.85] and u in [0.9, 1]: min is v, max is v, nothing left to compute.
    CHECK(PruneFor(p, {0.9, 1, 0.8, 0.85}).code.empty());
    // Touching ranges decide nothing: fmin(+0, -0) may be either, so only strict order counts.
    vm::Decisions touching = Record<vm::Interval>(p, {0.5, 0.6, 0.6, 0.7});
    CHECK(touching.operandAt(0) == 0);
    // The order is taken from the ranges: min(u + 0.01, u) is u at every point, but over a
    // region wider than 0.01 the ranges overlap and nothing is recorded.
    const vm::Program q = Hand({I(vm::Op::AddRK, 2, 0, 0), I(vm::Op::MinRR, 2, 2, 0)}, {0.01}, 3, 2);
    CHECK(Record<vm::Affine>(q, {0.2, 0.4, 0, 1}).operandAt(1) == 0);
    CHECK(Record<vm::Affine>(q, {0.2, 0.205, 0, 1}).operandAt(1) == 2);
}

TEST_CASE("decided values become constants, and constant operands constant forms", "[vm][prune]") {
    // z = floor(u * 4) * v + (u < 2): over u in [0.3, 0.4], floor(u*4) = 1 and u < 2 is 1.
    const vm::Program p = Hand({I(vm::Op::MulRK, 2, 0, 0), I(vm::Op::Floor, 2, 2), I(vm::Op::MulRR, 2, 2, 1),
                                I(vm::Op::LtRK, 3, 0, 1), I(vm::Op::AddRR, 2, 2, 3)},
                               {4.0, 2.0}, 4, 2);
    const vm::Program pruned = PruneFor(p, {0.3, 0.4, 0, 1});
    CHECK(Ops(pruned) == std::vector<vm::Op>{vm::Op::MulRK, vm::Op::AddRK});
    // A floor that is 0 is not taken as a constant (floor(-0.0) is -0.0), a false comparison is.
    vm::Decisions d = Record<vm::Affine>(p, {0.1, 0.2, 0, 1});
    double k = 1;
    CHECK_FALSE(d.constantAt(1, &k));
    vm::Decisions far = Record<vm::Affine>(Hand({I(vm::Op::LtRK, 2, 0, 0)}, {-1.0}, 3, 2), {0.1, 0.2, 0, 1});
    REQUIRE(far.constantAt(0, &k));
    CHECK(std::bit_cast<uint64_t>(k) == std::bit_cast<uint64_t>(0.0));
}

TEST_CASE("a program that takes derivatives keeps its constant register operands in registers", "[vm][prune]") {
    // z = 1 / Du(-v + c), c = 0 loaded into a register. Du(-v) is -0; -0 + R[c] (a dual constant,
    // derivative +0) has the derivative +0, so z = +inf. The constant form -0 + K[c] would keep
    // the derivative -0 and make z = -inf: with derivatives, pruning makes no constant forms.
    const vm::Program p = Hand({I(vm::Op::LoadK, 2, 0), I(vm::Op::Neg, 3, 1), I(vm::Op::AddRR, 3, 3, 2),
                                I(vm::Op::DerivU, 3, 3), I(vm::Op::DivKR, 3, 1, 3)},
                               {0.0, 1.0}, 4, 3);
    REQUIRE(p.usesDerivatives());
    CHECK(test::PointOnSquare(p, 0.5, 0.5).z == std::numeric_limits<double>::infinity());
    const vm::Program pruned = PruneFor(p, {0.2, 0.8, 0.2, 0.8});
    const std::vector<vm::Op> ops = Ops(pruned);
    CHECK(std::count(ops.begin(), ops.end(), vm::Op::AddRR) == 1);
    CHECK(std::count(ops.begin(), ops.end(), vm::Op::AddRK) == 0);
}

TEST_CASE("floor splitting: a choice decided differently by the two cases is undecided", "[vm][prune]") {
    // f = floor(u * 4) over u straddling 0.25 runs once with f = 0 and once with f = 1.
    // z = (f < 1.5 ? v : u) + (f == 0 ? v : u)
    const vm::Program p = Hand({I(vm::Op::MulRK, 2, 0, 0), I(vm::Op::Floor, 2, 2), I(vm::Op::LtRK, 3, 2, 1),
                                I(vm::Op::Select, 3, 3, 1), I(vm::Op::Ext, 0), I(vm::Op::EqRK, 2, 2, 2),
                                I(vm::Op::Select, 2, 2, 1), I(vm::Op::Ext, 0), I(vm::Op::AddRR, 2, 3, 2)},
                               {4.0, 1.5, 0.0}, 4, 2);
    const Region straddling{0.25 - 1e-3, 0.25 + 1e-3, 0.3, 0.6};
    for (const vm::Decisions& d : {Record<vm::Affine>(p, straddling), Record<vm::Interval>(p, straddling)}) {
        CHECK(d.operandAt(3) == 2);  // both cases: f < 1.5
        CHECK(d.operandAt(6) == 0);  // f == 0 in one case only
        double k;
        CHECK_FALSE(d.constantAt(1, &k));  // the floor is 0 in one case, 1 in the other
    }
    const vm::Program pruned = PruneFor(p, straddling);
    CHECK(Ops(pruned) ==
          std::vector<vm::Op>{vm::Op::MulRK, vm::Op::Floor, vm::Op::EqRK, vm::Op::Select, vm::Op::Ext, vm::Op::AddRR});
}

TEST_CASE("an unbounded condition decides nothing", "[vm][prune]") {
    // z = log(u - 2) > 0 ? u : v: the scalar condition is NaN > 0, false; the bound of log is
    // Unbounded, so the select must stay.
    const vm::Program p = Hand({I(vm::Op::SubRK, 2, 0, 0), I(vm::Op::Log, 2, 2), I(vm::Op::LtKR, 2, 1, 2),
                                I(vm::Op::Select, 2, 2, 0), I(vm::Op::Ext, 1)},
                               {2.0, 0.0}, 3, 2);
    for (const vm::Decisions& d : {Record<vm::Affine>(p, {0.1, 0.2, 0, 1}), Record<vm::Interval>(p, {0.1, 0.2, 0, 1})})
        CHECK(d.operandAt(3) == 0);
    CHECK(PruneFor(p, {0.1, 0.2, 0, 1}).code.size() == p.code.size());
}

TEST_CASE("recording is off by default and changes no result", "[vm][prune]") {
    compiler::CompiledShader s =
        test::CompileOrThrow("displacement t() { float h = u < 0.5 ? sin(v * 9) : min(v, u * u); P += N * h; }");
    vm::Interpreter<vm::Affine> plain(s.bound), recording(s.bound);
    recording.SetRecording(true);
    for (double u0 : {0.1, 0.45, 0.7}) {
        auto a = renderer::EvaluateOnPatch(plain, renderer::BilinearPatch::UnitSquare(), u0, u0 + 0.1, 0.2, 0.3,
                                           glm::dvec3(0.0), *s.bound.findOutput("P"));
        auto b = renderer::EvaluateOnPatch(recording, renderer::BilinearPatch::UnitSquare(), u0, u0 + 0.1, 0.2, 0.3,
                                           glm::dvec3(0.0), *s.bound.findOutput("P"));
        CHECK(a.z.toString() == b.z.toString());
    }
    CHECK(plain.decisions().size() == 0);
    CHECK(recording.decisions().size() == s.bound.code.size());
}
