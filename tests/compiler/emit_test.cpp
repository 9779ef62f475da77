// tests/compiler/emit_test.cpp: instruction selection (compiler/emit.*), from value graphs built
// by hand: a constant operand becomes a K operand where the opcode table has that form (second:
// RK; first: KR, or RK with the operands exchanged for a commutative operation), and is loaded
// into a register, once however many read it, where it has none; noise keeps its channel;
// parameters and outputs reach the program; what no output reads is not emitted. Every program
// must pass the verifier and compute, in doubles, the expression it was built from.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "compiler/emit.h"
#include "vm/interpreter.h"
#include "vm/verify.h"

using namespace affray;
using compiler::IrBuilder;
using compiler::IrOp;
using compiler::ValueId;
using vm::Op;

namespace {

/// The opcodes of `p`, Ext words included.
std::vector<Op> Opcodes(const vm::Program& p) {
    std::vector<Op> ops;
    for (const vm::Instr& in : p.code) ops.push_back(in.op);
    return ops;
}

/// A program whose output P is (x, y, z), verified.
vm::Program EmitP(const IrBuilder& ir, ValueId x, ValueId y, ValueId z,
                  const std::vector<vm::ProgramParam>& params = {}) {
    const vm::Program p = compiler::Emit(ir, {{"P", {compiler::Type::Point, {x, y, z}}}}, params);
    std::string error;
    CHECK(vm::Verify(p, &error));
    INFO(error);
    return p;
}

/// A program whose output P is (value, value, value).
vm::Program EmitP(const IrBuilder& ir, ValueId value) { return EmitP(ir, value, value, value); }

/// P at (u, v) in doubles.
vm::Vec3<double> RunAt(const vm::Program& p, double u, double v = 0) {
    vm::Interpreter<double> interp(p);
    interp.SetGlobal(vm::Global::u, u);
    interp.SetGlobal(vm::Global::v, v);
    interp.Run();
    return interp.OutputTriple(p.outputs[0]);
}

}  // namespace

TEST_CASE("emit: a constant operand takes the opcode's K form where it has one", "[compiler][emit]") {
    struct Case {
        const char* what;
        IrOp op;
        bool constantFirst;
        Op expected;
        double (*value)(double u);
    };
    const Case cases[] = {
        {"u - 3", IrOp::Sub, false, Op::SubRK, [](double u) { return u - 3; }},
        {"3 - u", IrOp::Sub, true, Op::SubKR, [](double u) { return 3 - u; }},
        {"u / 3", IrOp::Div, false, Op::DivRK, [](double u) { return u / 3; }},
        {"3 / u", IrOp::Div, true, Op::DivKR, [](double u) { return 3 / u; }},
        {"3 * u", IrOp::Mul, true, Op::MulRK, [](double u) { return 3 * u; }},  // commutative: exchanged
        {"min(3, u)", IrOp::Min, true, Op::MinRK, [](double u) { return std::min(3.0, u); }},
        {"u < 3", IrOp::Lt, false, Op::LtRK, [](double u) { return u < 3 ? 1.0 : 0.0; }},
        {"3 < u", IrOp::Lt, true, Op::LtKR, [](double u) { return 3 < u ? 1.0 : 0.0; }},
        {"pow(u, 3)", IrOp::Pow, false, Op::PowRK, [](double u) { return std::pow(u, 3); }},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        // The constant is made first: its id is the lower, so a commutative operation keeps it first.
        IrBuilder ir;
        const ValueId k = ir.Const(3), u = ir.Global(vm::Global::u, 0);
        const vm::Program p = EmitP(ir, c.constantFirst ? ir.Binary(c.op, k, u, 1) : ir.Binary(c.op, u, k, 1));
        REQUIRE(Opcodes(p) == std::vector<Op>{c.expected});
        CHECK(p.constants == std::vector<double>{3});
        const vm::Instr& in = p.code[0];
        // The register operand is u's, the K operand the constant's: in B or C as the form says.
        const bool kFirst = vm::Info(c.expected).format[1] == 'k';
        CHECK((kFirst ? in.b : in.c) == 0);
        CHECK((kFirst ? in.c : in.b) == p.globalRegisters[int(vm::Global::u)]);
        for (double u : {0.25, 5.0}) CHECK(RunAt(p, u).x == c.value(u));
    }
}

TEST_CASE("emit: a constant an opcode must read from a register is loaded once", "[compiler][emit]") {
    // atan(u, 2) + atan(v, 2): Atan2 has only the all-register form. The 2 is loaded once and
    // read by both.
    IrBuilder ir;
    const ValueId u = ir.Global(vm::Global::u, 0), v = ir.Global(vm::Global::v, 0), two = ir.Const(2);
    const ValueId sum = ir.Binary(IrOp::Add, ir.Binary(IrOp::Atan2, u, two, 1), ir.Binary(IrOp::Atan2, v, two, 1), 1);
    const vm::Program p = EmitP(ir, sum);
    CHECK(Opcodes(p) == std::vector<Op>{Op::LoadK, Op::Atan2RR, Op::Atan2RR, Op::AddRR});
    CHECK(p.constants == std::vector<double>{2});
    CHECK(p.code[1].c == p.code[0].a);  // both read the loaded register
    CHECK(p.code[2].c == p.code[0].a);
    CHECK(RunAt(p, 0.5, 0.25).x == std::atan2(0.5, 2.0) + std::atan2(0.25, 2.0));

    // Two constants of an operation with no K form at all (Select): each loaded.
    IrBuilder sel;
    const ValueId cond = sel.Binary(IrOp::Lt, sel.Global(vm::Global::u, 0), sel.Const(0.5), 1);
    const vm::Program s = EmitP(sel, sel.Select(cond, sel.Const(10), sel.Const(20), 2));
    CHECK(Opcodes(s) == std::vector<Op>{Op::LtRK, Op::LoadK, Op::LoadK, Op::Select, Op::Ext});
    CHECK(RunAt(s, 0.25).x == 10);
    CHECK(RunAt(s, 0.75).x == 20);
}

TEST_CASE("emit: constant outputs are loaded, unread nodes are not emitted, lines are kept", "[compiler][emit]") {
    IrBuilder ir;
    const ValueId u = ir.Global(vm::Global::u, 0), v = ir.Global(vm::Global::v, 0);
    ir.Unary(IrOp::Cos, v, 3);  // read by no output
    const ValueId sinU = ir.Unary(IrOp::Sin, u, 4);
    const ValueId half = ir.Const(0.5);
    const vm::Program p = EmitP(ir, half, sinU, half);
    CHECK(Opcodes(p) == std::vector<Op>{Op::Sin, Op::LoadK});
    CHECK(p.lines == std::vector<int>{4, 0});  // a constant has no line of its own
    CHECK_FALSE(p.readsGlobal(vm::Global::v));
    REQUIRE(p.outputs.size() == 1);
    CHECK(p.outputs[0].name == "P");
    CHECK(p.outputs[0].registers[0] == p.outputs[0].registers[2]);
    const vm::Vec3<double> at = RunAt(p, 0.3);
    CHECK(at.x == 0.5);
    CHECK(at.y == std::sin(0.3));
    CHECK(at.z == 0.5);
}

TEST_CASE("emit: noise keeps its channel in the flags, parameters get registers", "[compiler][emit]") {
    IrBuilder ir;
    const ValueId u = ir.Global(vm::Global::u, 0), v = ir.Global(vm::Global::v, 0);
    const ValueId amplitude = ir.Param(1, 0);
    const ValueId noise = ir.Call(IrOp::Noise, {u, v}, 2, 1);
    const ValueId scaled = ir.Binary(IrOp::Mul, amplitude, noise, 1);
    std::vector<vm::ProgramParam> params(2);
    params[0] = {"unread", "float", 1, vm::kNoRegister, {0}};
    params[1] = {"amp", "float", 1, vm::kNoRegister, {3}};
    const vm::Program p = EmitP(ir, scaled, scaled, scaled, params);
    CHECK(Opcodes(p) == std::vector<Op>{Op::Noise2, Op::MulRR});
    CHECK(p.code[0].flags == 2);
    REQUIRE(p.params.size() == 2);
    CHECK(p.params[0].firstRegister == vm::kNoRegister);
    CHECK(p.params[1].firstRegister != vm::kNoRegister);

    // The channel is the noise's seed: another channel is another value.
    IrBuilder other;
    const vm::Program q =
        EmitP(other, other.Call(IrOp::Noise, {other.Global(vm::Global::u, 0), other.Global(vm::Global::v, 0)}, 0, 1));
    CHECK(q.code[0].flags == 0);
    // The globals are written before each run (a run may reuse their registers).
    auto run = [](vm::Interpreter<double>& interp) {
        interp.SetGlobal(vm::Global::u, 0.3);
        interp.SetGlobal(vm::Global::v, 0.6);
        interp.Run();
        return interp.OutputTriple(interp.program().outputs[0]).x;
    };
    vm::Interpreter<double> a(p), b(q);
    const double byDefault = run(a);
    a.SetParam(1, {1});
    const double n2 = run(a);
    CHECK(byDefault == 3 * n2);  // amp's default
    a.SetParam(1, {-1});
    CHECK(run(a) == -n2);
    CHECK(run(b) != n2);
}
