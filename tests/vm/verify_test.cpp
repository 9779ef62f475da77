// tests/vm/verify_test.cpp: the bytecode verifier (vm/verify.*). A small program written word by
// word passes; each of its faults, put in one at a time, fails with the verifier's exact sentence
// naming the instruction (counted in words, Ext words included) and the register, constant, slot,
// global, parameter or output at fault. Random programs over every opcode value are
// tests/vm/conformance_test.cpp's verifier fuzz; damaged files, tests/vm/bytecode_file_test.cpp's.
#include <catch2/catch.hpp>

#include <memory>
#include <string>

#include "tests/test_util.h"
#include "vm/verify.h"

using namespace affray;
using vm::Global;
using vm::Instr;
using vm::Op;

namespace {

/// R1 := u * K0; P := (R1, R1, R1). Registers: u is r0.
vm::Program Valid() {
    vm::Program p;
    p.registerCount = 2;
    p.globalRegisters[int(Global::u)] = 0;
    p.constants = {2};
    p.code = {Instr{Op::MulRK, 0, 1, 0, 0}};
    p.outputs.push_back({"P", 3, {1, 1, 1}});
    return p;
}

/// The verifier's sentence for `p`, "" if it passes.
std::string Problem(const vm::Program& p) {
    std::string error;
    const bool ok = vm::Verify(p, &error);
    CHECK(ok == error.empty());
    return ok ? "" : error;
}

}  // namespace

TEST_CASE("verify: a well-formed program passes, an instruction may overwrite its own operand", "[vm][verify]") {
    CHECK(Problem(Valid()) == "");
    vm::Program p = Valid();
    p.code = {Instr{Op::MulRK, 0, 0, 0, 0}};  // r0 := r0 * 2
    p.outputs[0].registers = {0, 0, 0};
    CHECK(Problem(p) == "");
    p.lines = {4};
    CHECK(Problem(p) == "");
    CHECK(Problem(vm::IdentityProgram()) == "");
}

TEST_CASE("verify: the program's sizes", "[vm][verify]") {
    vm::Program p = Valid();
    p.registerCount = -1;
    CHECK(Problem(p) == "register count out of range");
    p.registerCount = vm::kMaxRegisters + 1;
    CHECK(Problem(p) == "register count out of range");
    p = Valid();
    p.constants.assign(vm::kMaxConstants + 1, 0.0);
    CHECK(Problem(p) == "too many constants");
    p = Valid();
    p.lines = {1, 2};
    CHECK(Problem(p) == "line table length differs from code length");
    p = Valid();
    p.textures = std::make_shared<vm::TextureSlots>(vm::kMaxTextureSlots + 1);
    CHECK(Problem(p) == "too many texture slots");
}

TEST_CASE("verify: globals and parameters must fit in the registers and be well described", "[vm][verify]") {
    vm::Program p = Valid();
    p.globalRegisters[int(Global::P)] = 0;  // three registers from r0: r2 is past the two
    CHECK(Problem(p) == "global P register out of range");

    p = Valid();
    p.params.push_back({"Km", "float", 0, vm::kNoRegister, {}});
    CHECK(Problem(p) == "parameter Km has a bad size");
    p.params[0] = {"Km", "point", 3, vm::kNoRegister, {1, 2}};
    CHECK(Problem(p) == "parameter Km has the wrong number of defaults");
    p.params[0] = {"Km", "point", 3, 1, {1, 2, 3}};
    CHECK(Problem(p) == "parameter Km register out of range");
    p.params[0] = {"Km", "point", 3, vm::kNoRegister, {1, 2, 3}};  // not read: no register needed
    CHECK(Problem(p) == "");

    // A parameter's registers count as written, as a global's do.
    p = Valid();
    p.globalRegisters[int(Global::u)] = vm::kNoRegister;
    CHECK(Problem(p) == "instruction 0: register r0 read before it is written");
    p.params.push_back({"Km", "float", 1, 0, {1}});
    CHECK(Problem(p) == "");
}

TEST_CASE("verify: each operand of an instruction, by its format letter", "[vm][verify]") {
    vm::Program p = Valid();
    p.code[0] = Instr{Op::MulRK, 0, 1, 5, 0};
    CHECK(Problem(p) == "instruction 0: register r5 out of range");
    p.code[0] = Instr{Op::MulRK, 0, 1, 1, 0};
    CHECK(Problem(p) == "instruction 0: register r1 read before it is written");
    p.code[0] = Instr{Op::MulRK, 0, 1, 0, 3};
    CHECK(Problem(p) == "instruction 0: constant k3 out of range");
    p.code[0] = Instr{Op::MulRK, 0, 9, 0, 0};
    CHECK(Problem(p) == "instruction 0: register r9 out of range");
    // The same numbers in another format: MulRR reads its C as a register.
    p.code[0] = Instr{Op::MulRR, 0, 1, 0, 0};
    CHECK(Problem(p) == "");
    p.code[0] = Instr{Op::MulRR, 0, 1, 0, 1};
    CHECK(Problem(p) == "instruction 0: register r1 read before it is written");
    // LoadK reads no register: its B is a constant, its C unused.
    p.code[0] = Instr{Op::LoadK, 0, 1, 0, 60000};
    CHECK(Problem(p) == "");
    p.code[0] = Instr{Op::LoadK, 0, 1, 1, 0};
    CHECK(Problem(p) == "instruction 0: constant k1 out of range");
}

TEST_CASE("verify: opcodes, Ext words and texture slots", "[vm][verify]") {
    vm::Program p = Valid();
    p.code[0].op = static_cast<Op>(200);
    CHECK(Problem(p) == "instruction 0: unknown opcode 200");
    p.code[0].op = static_cast<Op>(vm::kOpCount);
    CHECK(Problem(p) == "instruction 0: unknown opcode " + std::to_string(vm::kOpCount));
    p.code[0] = Instr{Op::Ext, 0, 1, 0, 0};
    CHECK(Problem(p) == "instruction 0: an Ext word without an instruction before it");

    // Select takes an Ext word: R1 := r0 ? r0 : r0, then the instruction after it is number 2.
    p = Valid();
    p.code = {Instr{Op::Select, 0, 1, 0, 0}, Instr{Op::Ext, 0, 0, 0, 0}};
    CHECK(Problem(p) == "");
    p.code.push_back(Instr{Op::AddRR, 0, 1, 1, 7});
    CHECK(Problem(p) == "instruction 2: register r7 out of range");
    p.code = {Instr{Op::Select, 0, 1, 0, 0}};
    CHECK(Problem(p) == "instruction 0: its operand words are missing");
    p.code = {Instr{Op::Select, 0, 1, 0, 0}, Instr{Op::Sin, 0, 1, 0, 0}};
    CHECK(Problem(p) == "instruction 0: its operand words are missing");
    p.code = {Instr{Op::Select, 0, 1, 0, 0}, Instr{Op::Ext, 0, 9, 0, 0}};
    CHECK(Problem(p) == "instruction 0: register r9 out of range");  // the fourth operand, in the Ext's A

    // Texture2 names its slot in the flags byte.
    p = Valid();
    p.code = {Instr{Op::Texture2, 1, 1, 0, 0}};
    CHECK(Problem(p) == "instruction 0: texture slot 1 out of range");
    p.textures = std::make_shared<vm::TextureSlots>(1);
    CHECK(Problem(p) == "instruction 0: texture slot 1 out of range");
    p.textures = std::make_shared<vm::TextureSlots>(2);
    CHECK(Problem(p) == "");
}

TEST_CASE("verify: outputs must be one or three registers, each written", "[vm][verify]") {
    vm::Program p = Valid();
    p.outputs[0].size = 2;
    CHECK(Problem(p) == "output P has a bad size");
    p = Valid();
    p.outputs[0].size = 1;
    CHECK(Problem(p) == "");
    p.outputs[0].registers[0] = 60000;
    CHECK(Problem(p) == "output P register out of range or never written");
    p = Valid();
    p.registerCount = 3;
    p.outputs[0].registers = {1, 2, 1};  // r2 is in range but nothing writes it
    CHECK(Problem(p) == "output P register out of range or never written");
}

TEST_CASE("verify: without a place for the sentence, a bad program is still refused", "[vm][verify]") {
    vm::Program p = Valid();
    CHECK(vm::Verify(p, nullptr));
    p.code[0].b = 999;
    CHECK_FALSE(vm::Verify(p, nullptr));
}

TEST_CASE("the verifier rejects malformed programs", "[vm][verify]") {
    // A compiled program passes; breaking it any of three ways fails.
    compiler::CompiledShader s = test::CompileOrThrow("displacement t() { P += sin(u) * N; }");
    std::string error;
    REQUIRE(vm::Verify(s.bound, &error));
    vm::Program bad = s.bound;
    bad.code[0].b = 999;
    CHECK_FALSE(vm::Verify(bad, &error));
    bad = s.bound;
    bad.code[0].op = static_cast<vm::Op>(200);
    CHECK_FALSE(vm::Verify(bad, &error));
    CHECK(error.find("unknown opcode") != std::string::npos);
    bad = s.bound;
    bad.outputs[0].registers[0] = 60000;
    CHECK_FALSE(vm::Verify(bad, &error));
}
