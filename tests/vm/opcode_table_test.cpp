// tests/vm/opcode_table_test.cpp: the one opcode table (vm/opcodes.h) and what is derived from it:
// docs/opcodes.md lists it as `affray opcodes` prints it, the constant forms the pruner uses are
// the hand-checked ones, the compiler's map lifts every opcode back to itself, and RSL compiles
// to the opcodes' operand forms.
#include <catch2/catch.hpp>

#include <cctype>
#include <set>
#include <string>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "compiler/opcode_map.h"
#include "tests/test_util.h"
#include "vm/disasm.h"
#include "vm/opcodes.h"

using namespace affray;

TEST_CASE("opcode table: docs/opcodes.md holds the table the opcode list gives", "[vm][opcodes]") {
    std::ifstream file(test::SourceDir() + "/docs/opcodes.md");
    REQUIRE(file);
    std::stringstream text;
    text << file.rdbuf();
    const std::string table = vm::OpcodeTable();
    INFO("regenerate the table in docs/opcodes.md with `affray opcodes`:\n" << table);
    CHECK(text.str().find(table) != std::string::npos);
    CHECK(table.find("| 62 | CellNoise4 |") != std::string::npos);
}

TEST_CASE("opcode table: the constant forms derived from the table", "[vm][opcodes]") {
    using vm::Op;
    // A constant second operand: the RK form wherever there is one.
    CHECK(vm::ConstantFormOf(Op::AddRR, 2) == Op::AddRK);
    CHECK(vm::ConstantFormOf(Op::PowRR, 2) == Op::PowRK);
    CHECK(vm::ConstantFormOf(Op::MinRR, 2) == Op::MinRK);
    CHECK(vm::ConstantFormOf(Op::Atan2RR, 2) == Op::Ext);
    // A constant first operand: the KR form, else the RK form with the operands swapped where
    // that is the same double bit for bit (+, *, ==, !=; not fmin or fmax, not pow).
    CHECK(vm::ConstantFormOf(Op::SubRR, 1) == Op::SubKR);
    CHECK(vm::ConstantFormOf(Op::LtRR, 1) == Op::LtKR);
    CHECK(vm::ConstantFormOf(Op::MulRR, 1) == Op::MulRK);
    CHECK(vm::ConstantFormOf(Op::NeRR, 1) == Op::NeRK);
    CHECK(vm::ConstantFormOf(Op::MinRR, 1) == Op::Ext);
    CHECK(vm::ConstantFormOf(Op::PowRR, 1) == Op::Ext);
    CHECK(vm::ConstantFormOf(Op::AndRR, 1) == Op::Ext);
    // Not two-operand register forms: none.
    CHECK(vm::ConstantFormOf(Op::AddRK, 2) == Op::Ext);
    CHECK(vm::ConstantFormOf(Op::Select, 2) == Op::Ext);
    CHECK(vm::ConstantFormOf(Op::Noise2, 2) == Op::Ext);
    // Truth values: comparisons and logic only.
    for (int i = 0; i < vm::kOpCount; ++i) {
        const Op op = static_cast<Op>(i);
        const bool logic = (op >= Op::LtRR && op <= Op::OrRR) || op == Op::Not;
        INFO(vm::Info(op).name);
        CHECK(vm::GivesTruth(op) == logic);
    }
}

/// The operands opcode `op` takes, read from its operation's RSL spelling in vm/opcodes.h ("pow(x,
/// y)": x and y; "c ? x : y": three) or, for noise, pnoise and cellnoise, from the dimension that
/// ends the opcode's name (pnoise takes a period per dimension too); for texture, the count that
/// ends its name (s and t, or the four corners' s and t); for the renderer's queries (Light,
/// Trace), their operands as vm/lights.h describes them.
int SpelledOperands(vm::Op op) {
    const vm::Operation f = vm::OperationOf(op);
    const std::string name = vm::Info(op).name;
    if (f == vm::Operation::Texture) return name.back() - '0';
    if (f == vm::Operation::Light) return 2;  // whether shadows are wanted, and the component
    if (f == vm::Operation::Trace) return 3;  // trace(P, R): the three components of R
    if (f == vm::Operation::Noise || f == vm::Operation::PNoise || f == vm::Operation::CellNoise) {
        const int dims = name.back() - '0';
        return f == vm::Operation::PNoise ? 2 * dims : dims;
    }
    std::set<char> names;
    const std::string rsl = vm::Info(f).rsl;
    for (size_t i = 0; i < rsl.size(); ++i) {
        const bool alone = (i == 0 || !std::isalpha(static_cast<unsigned char>(rsl[i - 1]))) &&
                           (i + 1 == rsl.size() || !std::isalpha(static_cast<unsigned char>(rsl[i + 1])));
        if (alone && std::isalpha(static_cast<unsigned char>(rsl[i]))) names.insert(rsl[i]);
    }
    // "x * x" (Sqr) names x twice: one operand.
    return static_cast<int>(names.size());
}

TEST_CASE("opcode table: every operation's opcodes lift to it and back", "[vm][opcodes]") {
    int rows = 0;
    for (int i = 0; i < vm::kOpCount; ++i) {
        const vm::Op op = static_cast<vm::Op>(i);
        const compiler::OpcodeRow* row = compiler::RowOf(op);
        INFO(vm::Info(op).name);
        if (vm::OperationOf(op) == vm::Operation::None) {
            CHECK(row == nullptr);
            continue;
        }
        REQUIRE(row);
        ++rows;
        CHECK(compiler::OpcodeFor(row->ir, row->count, row->form) == op);
        // The operand count against what the table does not build it from: the operation's RSL
        // spelling, or for the noise functions the dimension in the opcode's name.
        CHECK(row->count == SpelledOperands(op));
    }
    CHECK(rows == vm::kOpCount - 3);  // all but LoadK, Move and Ext
}

TEST_CASE("opcode table: RSL arithmetic and built-ins compile to each operand form", "[vm][opcodes]") {
    // The compiler's instruction selection end to end: one expression per opcode family (the
    // number types' rules for every opcode are tests/vm/conformance_test.cpp's).
    compiler::CompiledShader s = test::CompileOrThrow(R"(
        displacement all(float k = 3) {
            float a = u + 1, b = v + 2;
            float x = -a + (a + b) + (a + k) + (a - b) + (a - k) + (k - a) + a * b + a * k
                    + a / b + a / k + k / a + a * a + sqrt(a) + exp(a) + log(a) + sin(a) + cos(a)
                    + abs(a - 2) + sign(a - 1.2) + pow(a, b) + pow(a, 3.5) + Du(a * b) + Dv(a * b);
            P += vector(0, 0, x);
        })");
    std::vector<vm::Op> seen;
    for (const vm::Instr& in : s.bound.code) seen.push_back(in.op);
    for (vm::Op op : {vm::Op::Neg,   vm::Op::AddRR, vm::Op::AddRK, vm::Op::SubRR,  vm::Op::SubRK, vm::Op::SubKR,
                      vm::Op::MulRR, vm::Op::MulRK, vm::Op::DivRR, vm::Op::DivRK,  vm::Op::DivKR, vm::Op::Sqr,
                      vm::Op::Sqrt,  vm::Op::Exp,   vm::Op::Log,   vm::Op::Sin,    vm::Op::Cos,   vm::Op::Abs,
                      vm::Op::Sign,  vm::Op::PowRR, vm::Op::PowRK, vm::Op::DerivU, vm::Op::DerivV}) {
        INFO(vm::Info(op).name);
        CHECK(std::find(seen.begin(), seen.end(), op) != seen.end());
    }
    const double u = 0.3, v = 0.6;
    const double a = u + 1, b = v + 2, k = 3;
    const double expected = -a + (a + b) + (a + k) + (a - b) + (a - k) + (k - a) + a * b + a * k + a / b + a / k +
                            k / a + a * a + std::sqrt(a) + std::exp(a) + std::log(a) + std::sin(a) + std::cos(a) +
                            std::abs(a - 2) + 1.0 + std::pow(a, b) + std::pow(a, 3.5) + b + a;
    CHECK(test::EvalOnSquare<vm::Dual<double>>(s.bound, u, u, v, v).z.v == Approx(expected).epsilon(1e-12));
    // Without derivatives Du and Dv are unknown: NaN, never a silently wrong number.
    CHECK(std::isnan(test::EvalOnSquare<double>(s.bound, u, u, v, v).z));
}
