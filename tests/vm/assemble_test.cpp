// tests/vm/assemble_test.cpp: the back end that writes programs (vm/assemble.*), on small programs
// whose code is worked out by hand from the header's four rules: operations no output needs are
// dropped with the inputs only they read; inputs take blocks of registers, globals by number then
// parameters by index; each result takes the lowest register free at that point, an operand read
// for the last time freed first; the constant pool keeps each value the kept code reads once, and
// Load makes one LoadK per value (by its bits: 0 and -0 are two). Every program made here must
// also pass the verifier and compute, in doubles, what its operations say.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "vm/assemble.h"
#include "vm/disasm.h"
#include "vm/interpreter.h"
#include "vm/verify.h"

using namespace affray;
using vm::Assembler;
using vm::Global;
using vm::Op;

namespace {

/// One instruction word as the tests write them.
struct Word {
    Op op;
    uint16_t a, b, c;
};

/// The code of `program` as words (flags are checked where they matter).
std::vector<Word> CodeOf(const vm::Program& program) {
    std::vector<Word> out;
    for (const vm::Instr& in : program.code) out.push_back({in.op, in.a, in.b, in.c});
    return out;
}

bool operator==(const Word& x, const Word& y) { return x.op == y.op && x.a == y.a && x.b == y.b && x.c == y.c; }

std::ostream& operator<<(std::ostream& os, const Word& w) {
    return os << vm::Info(w.op).name << " " << w.a << " " << w.b << " " << w.c;
}

/// An output of one value (three times: outputs hold one or three).
Assembler::Output Out(const std::string& name, Assembler::ValueId v) { return {name, 3, {v, v, v}}; }

/// Finishes `as` into a program that must pass the verifier.
vm::Program Finish(Assembler& as, const std::vector<Assembler::Output>& outputs,
                   const std::vector<vm::ProgramParam>& params = {}, bool lines = false) {
    vm::Program p;
    as.Finish(outputs, params, lines, &p);
    std::string error;
    INFO(vm::Disassemble(p, ""));
    CHECK(vm::Verify(p, &error));
    INFO(error);
    return p;
}

/// Output `name`'s x in doubles with u and v set.
double RunAt(const vm::Program& p, double u, double v, const char* name = "P") {
    vm::Interpreter<double> interp(p);
    interp.SetGlobal(Global::u, u);
    interp.SetGlobal(Global::v, v);
    interp.Run();
    return interp.OutputTriple(*p.findOutput(name)).x;
}

}  // namespace

TEST_CASE("assemble: an operation no output needs is dropped, with the input only it read", "[vm][assemble]") {
    Assembler as;
    const int u = as.Global(Global::u);
    const int v = as.Global(Global::v);
    const int two = as.Constant(2);
    const int ops1[] = {u, two};
    const int twiceU = as.Operation(Op::MulRK, ops1, 1);
    const int ops2[] = {v};
    as.Operation(Op::Sin, ops2, 2);  // nothing reads sin(v)
    const vm::Program p = Finish(as, {Out("P", twiceU)});
    // u is r0; its last reader frees it, so 2u takes r0 again. v is read only by the dead Sin.
    CHECK(p.globalRegisters[int(Global::u)] == 0);
    CHECK_FALSE(p.readsGlobal(Global::v));
    CHECK(CodeOf(p) == std::vector<Word>{{Op::MulRK, 0, 0, 0}});
    CHECK(p.constants == std::vector<double>{2});
    CHECK(p.registerCount == 1);
    REQUIRE(p.outputs.size() == 1);
    CHECK(p.outputs[0].registers == std::array<uint16_t, 3>{0, 0, 0});
    CHECK(RunAt(p, 0.375, 0.5) == 0.75);
}

TEST_CASE("assemble: a result takes the lowest free register, operands read for the last time freed first",
          "[vm][assemble]") {
    // (u + v) * sin(u): u is r0 and v r1. u + v frees v (its last reader) and takes r1; sin(u)
    // frees u and takes r0; the product frees both and takes r0. Two registers in all.
    Assembler as;
    const int u = as.Global(Global::u);
    const int v = as.Global(Global::v);
    const int sumOps[] = {u, v};
    const int sum = as.Operation(Op::AddRR, sumOps, 1);
    const int sinOps[] = {u};
    const int sinU = as.Operation(Op::Sin, sinOps, 1);
    const int mulOps[] = {sum, sinU};
    const int product = as.Operation(Op::MulRR, mulOps, 1);
    const vm::Program p = Finish(as, {Out("P", product)});
    CHECK(CodeOf(p) == std::vector<Word>{{Op::AddRR, 1, 0, 1}, {Op::Sin, 0, 0, 0}, {Op::MulRR, 0, 1, 0}});
    CHECK(p.registerCount == 2);
    CHECK(p.outputs[0].registers[0] == 0);
    CHECK(RunAt(p, 0.25, 0.5) == (0.25 + 0.5) * std::sin(0.25));
}

TEST_CASE("assemble: a value an output reads keeps its register to the end", "[vm][assemble]") {
    // N's value u + v is read by the product too, but as an output it is never freed: the
    // product takes a register of its own.
    Assembler as;
    const int u = as.Global(Global::u);
    const int v = as.Global(Global::v);
    const int sumOps[] = {u, v};
    const int sum = as.Operation(Op::AddRR, sumOps, 1);
    const int mulOps[] = {sum, sum};
    const int square = as.Operation(Op::MulRR, mulOps, 1);
    const vm::Program p = Finish(as, {Out("P", square), Out("N", sum)});
    CHECK(CodeOf(p) == std::vector<Word>{{Op::AddRR, 0, 0, 1}, {Op::MulRR, 1, 0, 0}});
    CHECK(p.outputs[0].registers[0] == 1);
    CHECK(p.outputs[1].registers[0] == 0);
    CHECK(RunAt(p, 0.25, 0.5, "P") == 0.5625);
    CHECK(RunAt(p, 0.25, 0.5, "N") == 0.75);
}

TEST_CASE("assemble: the constant pool keeps each value the kept code reads once", "[vm][assemble]") {
    Assembler as;
    const int u = as.Global(Global::u);
    const int half1 = as.Constant(0.5), half2 = as.Constant(0.5), three = as.Constant(3), unused = as.Constant(99);
    const int a1[] = {u, half1};
    const int a = as.Operation(Op::MulRK, a1, 1);
    const int b1[] = {a, half2};
    const int b = as.Operation(Op::AddRK, b1, 1);
    const int d1[] = {u, unused};
    as.Operation(Op::AddRK, d1, 1);  // dead: 99 is not pooled
    const int c1[] = {three, b};
    const int c = as.Operation(Op::SubKR, c1, 1);
    const vm::Program p = Finish(as, {Out("P", c)});
    CHECK(p.constants == std::vector<double>{0.5, 3});
    CHECK(CodeOf(p) == std::vector<Word>{{Op::MulRK, 0, 0, 0}, {Op::AddRK, 0, 0, 0}, {Op::SubKR, 0, 1, 0}});
    CHECK(RunAt(p, 0.25, 0) == 3 - (0.25 * 0.5 + 0.5));
}

TEST_CASE("assemble: Load makes one LoadK per constant value, told apart by its bits", "[vm][assemble]") {
    Assembler as;
    const int seven = as.Load(7, 1);
    CHECK(as.Load(7, 2) == seven);
    const int zero = as.Load(0.0, 3);
    const int minusZero = as.Load(-0.0, 4);
    CHECK(minusZero != zero);
    CHECK(as.Load(0.0, 5) == zero);
    // P = (7 + 0, -0, 0): the two zeros are two registers, two constants.
    const int sumOps[] = {seven, zero};
    const int sum = as.Operation(Op::AddRR, sumOps, 6);
    const vm::Program p = Finish(as, {{"P", 3, {sum, minusZero, zero}}}, {}, true);
    REQUIRE(p.constants.size() == 3);
    CHECK(p.constants[0] == 7);
    CHECK(!std::signbit(p.constants[1]));
    CHECK(std::signbit(p.constants[2]));
    // The loads come in the order they were made, each with the line of its first Load; the
    // zero is an output, so the sum does not take its register.
    CHECK(CodeOf(p) ==
          std::vector<Word>{{Op::LoadK, 0, 0, 0}, {Op::LoadK, 1, 1, 0}, {Op::LoadK, 2, 2, 0}, {Op::AddRR, 0, 0, 1}});
    CHECK(p.lines == std::vector<int>{1, 3, 4, 6});
    CHECK(p.registerCount == 3);
    vm::Interpreter<double> interp(p);
    interp.Run();
    const vm::Vec3<double> out = interp.OutputTriple(p.outputs[0]);
    CHECK(out.x == 7);
    CHECK((out.y == 0 && std::signbit(out.y)));
    CHECK((out.z == 0 && !std::signbit(out.z)));
}

TEST_CASE("assemble: inputs are placed globals by number, then parameters by index, only if read", "[vm][assemble]") {
    // Read: P.y and the third component of parameter 1. Blocks: P (global 0) r0..r2, then
    // parameter 1 r3..r5; u and parameter 0 are read by nothing. The components nobody reads
    // (r0, r2, r3, r4) are free from the start, so the sum takes r0.
    Assembler as;
    const int param1 = as.Param(1, 3);
    const int u = as.Global(Global::u);
    const int pos = as.Global(Global::P);
    CHECK(as.Global(Global::P) == pos);  // asked again: the same block
    CHECK(as.Param(1, 3) == param1);
    const int sumOps[] = {pos + 1, param1 + 2};
    const int sum = as.Operation(Op::AddRR, sumOps, 1);
    const int deadOps[] = {u};
    as.Operation(Op::Cos, deadOps, 1);
    std::vector<vm::ProgramParam> params(2);
    params[0] = {"a", "float", 1, 42, {1}};  // a register given here is not kept
    params[1] = {"b", "point", 3, vm::kNoRegister, {4, 5, 6}};
    const vm::Program p = Finish(as, {Out("P", sum)}, params);
    CHECK(p.globalRegisters[int(Global::P)] == 0);
    CHECK_FALSE(p.readsGlobal(Global::u));
    REQUIRE(p.params.size() == 2);
    CHECK(p.params[0].firstRegister == vm::kNoRegister);
    CHECK(p.params[1].firstRegister == 3);
    CHECK(p.params[1].defaults == std::vector<double>{4, 5, 6});
    CHECK(CodeOf(p) == std::vector<Word>{{Op::AddRR, 0, 1, 5}});
    CHECK(p.registerCount == 6);
    vm::Interpreter<double> interp(p);
    interp.SetGlobal(Global::P, vm::Vec3<double>{10, 20, 30});
    interp.Run();
    CHECK(interp.OutputTriple(p.outputs[0]).x == 26);  // P.y + the default 6
}

TEST_CASE("assemble: an instruction of several words takes its operands in its Ext words, each with its line",
          "[vm][assemble]") {
    // u < 0.5 ? u : v. Select's format is wrrr--: A B C in the first word, its fourth operand in
    // the Ext's A. u (r0) is read again by the Select, so the comparison takes r2.
    auto finish = [](bool lines) {
        Assembler as;
        const int u = as.Global(Global::u);
        const int v = as.Global(Global::v);
        const int lessOps[] = {u, as.Constant(0.5)};
        const int less = as.Operation(Op::LtRK, lessOps, 3);
        const int selectOps[] = {less, u, v};
        return Finish(as, {Out("P", as.Operation(Op::Select, selectOps, 7))}, {}, lines);
    };
    const vm::Program p = finish(true);
    CHECK(CodeOf(p) == std::vector<Word>{{Op::LtRK, 2, 0, 0}, {Op::Select, 0, 2, 0}, {Op::Ext, 1, 0, 0}});
    CHECK(p.lines == std::vector<int>{3, 7, 7});
    CHECK(RunAt(p, 0.25, 0.75) == 0.25);
    CHECK(RunAt(p, 0.625, 0.75) == 0.75);
    // Without lines the table is empty and the code the same.
    const vm::Program noLines = finish(false);
    CHECK(noLines.lines.empty());
    CHECK(CodeOf(noLines) == CodeOf(p));
}

TEST_CASE("assemble: Clear forgets the last program, Finish overwrites what it writes", "[vm][assemble]") {
    auto build = [](Assembler& as) {
        const int v = as.Global(Global::v);
        const int ops[] = {v};
        return Out("P", as.Operation(Op::Sqr, ops, 2));
    };
    Assembler fresh;
    const Assembler::Output freshOut = build(fresh);
    vm::Program expected;
    fresh.Finish({freshOut}, {}, true, &expected);

    Assembler reused;
    const int u = reused.Global(Global::u);
    const int ops[] = {u, reused.Constant(5)};
    vm::Program p;
    reused.Finish({Out("P", reused.Operation(Op::AddRK, ops, 1))}, {}, true, &p);
    reused.Clear();
    const Assembler::Output out = build(reused);
    p.shaderName = "kept";
    reused.Finish({out}, {}, true, &p);
    CHECK(CodeOf(p) == CodeOf(expected));
    CHECK(p.constants.empty());
    CHECK(p.lines == expected.lines);
    CHECK_FALSE(p.readsGlobal(Global::u));
    CHECK(p.globalRegisters == expected.globalRegisters);
    CHECK(p.shaderName == "kept");  // not Finish's to write
    CHECK(RunAt(p, 0, 0.5) == 0.25);
}
