// tests/compiler/fold_test.cpp: folding is the VM. A constant the compiler folds must be the value
// the scalar VM computes at run time, bit for bit, for every foldable operation of the opcode table
// (vm/opcodes.h) and on the edge values: signed zeros, subnormals, huge values, and operands whose
// result overflows or is NaN (never folded: the run time computes and reports those).
//  0. The reference: every scalar operation's value, at run time (the scalar VM) and folded, equals
//     the one written here from <cmath> and the documented rules (Reference), not through the VM
//     (the folder runs the scalar VM, so comparing the two alone could not fail).
//  1. The IR: every foldable operation, every operand count, on tuples of edge values: folded
//     exactly when the operands and the result are finite, and then to the scalar VM's value.
//  2. End to end: a shader computing the operation from its parameters, run generically (the
//     parameters in registers) and specialised for the same values (everything folded), must give
//     the same double: the drift of a hand-written folding rule (sign(-0) was +0 folded, -0 at
//     run time) shows here.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "compiler/compile.h"
#include "compiler/ir.h"
#include "tests/test_random.h"
#include "tests/test_util.h"
#include "vm/interpreter.h"

using namespace affray;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Edge values: signed zeros, small integers and halves, subnormals, huge magnitudes, the largest
/// double, values whose exp or pow overflows, and (for the IR) the non-finite ones.
const std::vector<double> kFinite = {
    0.0,   -0.0, 1.0, -1.0, 0.5, -2.5, 3.0, 4.9e-324, -2.2250738585072e-308, 1e300, -1e308, 1.7976931348623157e308,
    710.0, -0.75};
const std::vector<double> kNonFinite = {kInf, -kInf, kNaN};

bool SameDouble(double a, double b) {
    return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b) || (std::isnan(a) && std::isnan(b));
}

/// Every tuple of `count` values from `values` (all of them for up to 3 operands, else `samples`
/// random ones).
std::vector<std::vector<double>> Tuples(const std::vector<double>& values, int count, int samples, uint64_t seed) {
    std::vector<std::vector<double>> out;
    const size_t n = values.size();
    size_t total = 1;
    for (int i = 0; i < count; ++i) total *= n;
    if (count <= 3) {
        for (size_t k = 0; k < total; ++k) {
            std::vector<double> t;
            for (size_t r = k, i = 0; i < size_t(count); ++i, r /= n) t.push_back(values[r % n]);
            out.push_back(t);
        }
        return out;
    }
    test::Rng rng(seed);
    for (int s = 0; s < samples; ++s) {
        std::vector<double> t;
        t.reserve(static_cast<size_t>(count));
        for (int i = 0; i < count; ++i) t.push_back(values[static_cast<size_t>(rng.uniform(0, double(n))) % n]);
        out.push_back(t);
    }
    return out;
}

/// The channel the noise operations are asked for (the others ignore it).
constexpr uint8_t kChannel = 2;

/// What the compiler folds operation f on the constants x to (empty: not folded).
std::optional<double> FoldedValue(vm::Operation f, const std::vector<double>& x) {
    compiler::IrBuilder ir;
    compiler::IrNode n;
    n.op = compiler::IrOpOf(f);
    n.count = static_cast<uint8_t>(x.size());
    n.channel = kChannel;
    for (size_t k = 0; k < x.size(); ++k) n.in[k] = ir.Const(x[k]);
    return ir.ConstValue(ir.Create(n));
}

/// What RSL and the VM's documented rules (vm/numbers/number.h) say operation f gives on x,
/// written here from <cmath> and the rules, not through the VM: the reference both the folded
/// and the run-time value must equal. Empty for the noise functions (their values are
/// tests/vm/numbers/noise_test.cpp's) and the derivatives (not foldable).
std::optional<double> Reference(vm::Operation f, const std::vector<double>& x) {
    using F = vm::Operation;
    const double a = x[0], b = x.size() > 1 ? x[1] : 0.0;
    const auto truth = [](bool t) { return t ? 1.0 : 0.0; };
    switch (f) {
        case F::Neg: return -a;
        case F::Sqr: return a * a;
        case F::Sqrt: return a < 0 ? 0.0 : std::sqrt(a);  // a negative argument is 0 (-0 stays)
        case F::Exp: return std::exp(a);
        case F::Log: return std::log(a);
        case F::Sin: return std::sin(a);
        case F::Cos: return std::cos(a);
        case F::Tan: return std::tan(a);
        case F::Abs: return std::fabs(a);
        case F::Sign: return a > 0 ? 1.0 : a < 0 ? -1.0 : a;  // a signed zero and NaN stay
        case F::Floor: return std::floor(a);
        case F::Ceil: return std::ceil(a);
        case F::Round: return std::round(a);  // halves away from zero
        case F::Asin: return std::asin(a);
        case F::Acos: return std::acos(a);
        case F::Atan: return std::atan(a);
        case F::Not: return truth(a == 0);
        case F::Add: return a + b;
        case F::Sub: return a - b;
        case F::Mul: return a * b;
        case F::Div: return b == 0 ? a / 0.0 : a / b;  // a zero divisor is +0 whatever its sign
        case F::Pow:                                   // a negative base with a non-integer exponent is +0
            return a < 0 && std::floor(b) != b ? std::pow(0.0, b) : std::pow(a, b);
        case F::Min: return std::isnan(a) ? b : std::isnan(b) ? a : b < a ? b : a;  // equal: the first
        case F::Max: return std::isnan(a) ? b : std::isnan(b) ? a : a < b ? b : a;
        case F::Atan2: return std::atan2(a, b);  // atan(y, x): y first
        case F::Lt: return truth(a < b);
        case F::Le: return truth(a <= b);
        case F::Eq: return truth(a == b);
        case F::Ne: return truth(a != b);
        case F::And: return truth(a != 0 && b != 0);  // NaN is true
        case F::Or: return truth(a != 0 || b != 0);
        case F::Select: return a != 0 ? b : x[2];
        default: return std::nullopt;
    }
}

}  // namespace

TEST_CASE("folding: every scalar opcode computes its operation's reference value, at run time and folded",
          "[compiler][fold]") {
    std::vector<double> all = kFinite;
    all.insert(all.end(), kNonFinite.begin(), kNonFinite.end());
    int checked = 0;
    std::set<vm::Operation> operations;
    for (int i = 0; i < vm::kOpCount; ++i) {
        const vm::Op op = static_cast<vm::Op>(i);
        const vm::Operation f = vm::OperationOf(op);
        if (vm::FormOf(op) != vm::OperandForm::RR || !vm::Has(f, vm::kFoldable)) continue;
        const int count = vm::OperandCount(op);
        for (const std::vector<double>& x : Tuples(all, count, 300, 29 + uint64_t(i))) {
            const std::optional<double> want = Reference(f, x);
            if (!want) break;
            operations.insert(f);
            const double vmValue = vm::RunScalarOpcode(op, x.data(), kChannel);
            INFO(vm::Info(op).name << " on " << ::Catch::Detail::stringify(x) << ": VM " << vmValue << ", reference "
                                   << *want);
            CHECK(SameDouble(vmValue, *want));
            if (const std::optional<double> folded = FoldedValue(f, x)) {
                // x * 0 => 0 is compiler/fold.cpp's one algebraic rule that differs from the
                // operation on infinite or NaN x.
                const bool timesZero = f == vm::Operation::Mul && (x[0] == 0 || x[1] == 0);
                CHECK((SameDouble(*folded, *want) || (timesZero && *folded == 0)));
            }
            ++checked;
        }
    }
    // Every scalar operation of the table (all but the noise functions): 17 unary, 14 binary, Select.
    CHECK(operations.size() == 32);
    CHECK(checked == 17 * 17 + 14 * 17 * 17 + 17 * 17 * 17);
}

TEST_CASE("folding: every foldable opcode folds to the scalar VM's value, and only finite values fold",
          "[compiler][fold]") {
    std::vector<double> all = kFinite;
    all.insert(all.end(), kNonFinite.begin(), kNonFinite.end());
    int folded = 0, checked = 0, opcodes = 0, leftToRunTime = 0;
    for (int i = 0; i < vm::kOpCount; ++i) {
        const vm::Op op = static_cast<vm::Op>(i);
        const vm::Operation f = vm::OperationOf(op);
        if (!vm::Has(f, vm::kFoldable) || vm::FormOf(op) != vm::OperandForm::RR) continue;
        ++opcodes;
        const int count = vm::OperandCount(op);
        for (const std::vector<double>& x : Tuples(all, count, 300, 17 + uint64_t(i))) {
            const std::optional<double> k = FoldedValue(f, x);
            const double vmValue = vm::RunScalarOpcode(op, x.data(), kChannel);
            bool finiteInputs = true;
            for (double v : x) finiteInputs = finiteInputs && std::isfinite(v);
            INFO(vm::Info(op).name << " on " << ::Catch::Detail::stringify(x) << ": VM " << vmValue);
            ++checked;
            if (finiteInputs && std::isfinite(vmValue)) {
                REQUIRE(k.has_value());
                CHECK(SameDouble(*k, vmValue));
                ++folded;
            } else if (finiteInputs) {
                // Finite constants whose result overflows or is NaN (exp(1e300), 0/0, log(-1)):
                // not folded, whatever the rules; the run time computes and reports it.
                CHECK_FALSE(k.has_value());
                ++leftToRunTime;
            } else if (k) {
                // Not a fold of the operation on these constants but an algebraic rule that needs
                // no value: the same double, except x * 0 => 0 (compiler/fold.cpp's one documented
                // exception, for infinite or NaN x).
                const bool timesZero = f == vm::Operation::Mul && (x[0] == 0 || x[1] == 0);
                CHECK((SameDouble(*k, vmValue) || (timesZero && *k == 0)));
            }
        }
    }
    CHECK(opcodes >= 40);
    CHECK(folded > 1000);
    CHECK(leftToRunTime > 0);
    CHECK(checked > folded);
}

TEST_CASE("folding: a shader specialised for constant parameters computes what it computes generically",
          "[compiler][fold]") {
    int compared = 0;
    for (int i = 1; i < vm::kOperationCount; ++i) {
        const vm::Operation f = static_cast<vm::Operation>(i);
        if (!vm::Has(f, vm::kFoldable)) continue;
        // The operation's RSL spelling on the parameters x, y and c.
        std::string expr = vm::Info(f).rsl;
        auto replace = [&](const std::string& from, const std::string& to) {
            for (size_t at = expr.find(from); at != std::string::npos; at = expr.find(from, at + to.size()))
                expr.replace(at, from.size(), to);
        };
        replace("period", "y");
        replace("(p", "(x");
        // A truth value is not a float: as one, through a condition.
        if (vm::Has(f, vm::kTruth)) expr = "(" + expr + ") ? 1 : 0";
        const std::string source =
            "displacement t(float x = 0; float y = 0; float c = 0) {\n    P = point(" + expr + ", 0, 0);\n}\n";
        INFO(source);
        compiler::CompileResult r = compiler::CompileSource("fold.sl", source);
        INFO(r.diagnostics);
        REQUIRE(r.ok());
        const vm::Program& generic = r.shader->genericBound;
        const vm::ProgramOutput* out = generic.findOutput("P");
        REQUIRE(out);
        vm::Interpreter<double> run(generic);
        const int operands = vm::Info(f).operands == 3 ? 3 : 2;
        for (const std::vector<double>& x : Tuples(kFinite, operands, 0, 0)) {
            const double c = operands == 3 ? x[0] : 0.0, a = operands == 3 ? x[1] : x[0], b = x[operands - 1];
            const std::vector<compiler::ParamOverride> values = {{"x", {a}}, {"y", {b}}, {"c", {c}}};
            for (size_t p = 0; p < generic.params.size(); ++p) {
                const std::string& name = generic.params[p].name;
                run.SetParam(p, {name == "x" ? a : name == "y" ? b : c});
            }
            run.Run();
            const double atRunTime = run.OutputTriple(*out).x;
            std::vector<std::string> errors;
            std::optional<vm::Program> special = compiler::Specialise(generic, values, &errors);
            REQUIRE(special);
            vm::Interpreter<double> folded(*special);
            folded.Run();
            const double specialised = folded.OutputTriple(*special->findOutput("P")).x;
            INFO("x = " << a << ", y = " << b << ", c = " << c << ": generic " << atRunTime << ", specialised "
                        << specialised);
            CHECK(SameDouble(atRunTime, specialised));
            ++compared;
        }
    }
    CHECK(compared > 5000);
}

TEST_CASE("folding: sign keeps the sign of zero and NaN, as the VM does", "[compiler][fold]") {
    // Regression test (issue 14): the folder computed sign as (a > 0) - (a < 0), +0 for -0.
    compiler::CompileResult r =
        compiler::CompileSource("sign.sl", "displacement t(float x = -0.0) { P = point(sign(x), 0, 0); }\n");
    REQUIRE(r.ok());
    vm::Interpreter<double> run(r.shader->bound);
    run.Run();
    const double s = run.OutputTriple(*r.shader->bound.findOutput("P")).x;
    CHECK(s == 0.0);
    CHECK(std::signbit(s));
}
