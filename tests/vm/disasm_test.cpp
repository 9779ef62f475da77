// tests/vm/disasm_test.cpp: the listings of vm/disasm.* as text, exactly: one instruction's
// mnemonic padded to eight columns, its operands by format letter (registers, constants with their
// values, unused letters left out, Ext words' operands after the first word's), its noise channel
// or texture slot; damaged instructions said, not read past the code; and a whole program's header
// (globals read, outputs, texture slots) and its source lines shown where they change. The table
// of opcodes (OpcodeTable) is tests/vm/opcode_table_test.cpp's.
#include <catch2/catch.hpp>

#include <memory>
#include <string>

#include "tests/test_util.h"
#include "vm/disasm.h"

using namespace affray;
using vm::Instr;
using vm::Op;

namespace {

/// A program of these words and constants (nothing else set).
vm::Program WithCode(std::vector<Instr> code, std::vector<double> constants = {}) {
    vm::Program p;
    p.code = std::move(code);
    p.constants = std::move(constants);
    return p;
}

/// The listing of the instruction at `pc` of `p`.
std::string At(const vm::Program& p, size_t pc) { return vm::DisassembleInstr(p, &p.code[pc], p.code.size() - pc); }

}  // namespace

TEST_CASE("disasm: one instruction, operand by operand", "[vm][disasm]") {
    const vm::Program p = WithCode(
        {
            Instr{Op::MulRK, 0, 4, 3, 0},       // 0
            Instr{Op::LoadK, 0, 2, 1, 9},       // 1: C unused
            Instr{Op::SubKR, 0, 1, 0, 2},       // 2
            Instr{Op::Select, 0, 4, 4, 3},      // 3
            Instr{Op::Ext, 0, 0, 0, 0},         // 4
            Instr{Op::Noise1, 2, 4, 4, 0},      // 5
            Instr{Op::CellNoise1, 0, 4, 4, 0},  // 6: a name of 8 letters or more
            Instr{Op::Texture2, 1, 4, 3, 3},    // 7
            Instr{Op::AddRK, 0, 1, 2, 7},       // 8: a constant past the pool
        },
        {0.5, 1e-10, -3});
    CHECK(At(p, 0) == "MulRK   r4, r3, k0 (0.5)");
    CHECK(At(p, 1) == "LoadK   r2, k1 (1e-10)");
    CHECK(At(p, 2) == "SubKR   r1, k0 (0.5), r2");
    CHECK(At(p, 3) == "Select  r4, r4, r3, r0");
    CHECK(At(p, 5) == "Noise1  r4, r4  [channel 2]");
    CHECK(At(p, 6) == "CellNoise1 r4, r4");
    CHECK(At(p, 7) == "Texture2 r4, r3, r3  [texture 1]");
    CHECK(At(p, 8) == "AddRK   r1, r2, k7");
    // Constants print to nine significant digits.
    const vm::Program q = WithCode({Instr{Op::LoadK, 0, 0, 0, 0}}, {1.0 / 3});
    CHECK(At(q, 0) == "LoadK   r0, k0 (0.333333333)");
}

TEST_CASE("disasm: an unknown opcode or missing Ext words are said, nothing is read past the code", "[vm][disasm]") {
    vm::Program p = WithCode({Instr{static_cast<Op>(200), 0, 1, 2, 3}, Instr{Op::Select, 0, 1, 2, 3}});
    CHECK(At(p, 0) == "<bad opcode 200>");
    CHECK(At(p, 1) == "Select <operands missing>");
    // The whole listing goes on past a bad word, one word at a time.
    CHECK(vm::Disassemble(p, "") ==
          "; shader : 2 instructions, 0 registers, 0 constants\n"
          "; globals read: none\n"
          "   0  <bad opcode 200>\n"
          "   1  Select <operands missing>\n");
}

TEST_CASE("disasm: a program's header, and its source lines where they change", "[vm][disasm]") {
    vm::Program p = WithCode(
        {
            Instr{Op::MulRK, 0, 4, 3, 0},
            Instr{Op::Select, 0, 4, 4, 3},
            Instr{Op::Ext, 0, 0, 0, 0},
            Instr{Op::AddRR, 0, 4, 4, 3},
            Instr{Op::Sin, 0, 4, 4, 0},
        },
        {2});
    p.shaderName = "d";
    p.registerCount = 5;
    p.globalRegisters[int(vm::Global::P)] = 0;
    p.globalRegisters[int(vm::Global::u)] = 3;
    p.outputs.push_back({"P", 3, {4, 1, 2}});
    p.outputs.push_back({"h", 1, {4, vm::kNoRegister, vm::kNoRegister}});
    p.lines = {2, 3, 3, 3, 0};
    const std::string source = "displacement d() {\n    float x = u * 2;\n\tx = x ? x : P;  \n}\n";
    CHECK(vm::Disassemble(p, source) ==
          "; shader d: 5 instructions, 5 registers, 1 constants\n"
          "; globals read: P=r0..r2 u=r3\n"
          "; output P = r4 r1 r2\n"
          "; output h = r4\n"
          "; 2: float x = u * 2;\n"
          "   0  MulRK   r4, r3, k0 (2)\n"
          "; 3: x = x ? x : P;  \n"
          "   1  Select  r4, r4, r3, r0\n"
          "   3  AddRR   r4, r4, r3\n"
          "   4  Sin     r4, r4\n");
    // Without the source, the line numbers alone; without a line table, none.
    CHECK(vm::Disassemble(p, "").find("; 2: \n   0  MulRK") != std::string::npos);
    p.lines.clear();
    CHECK(vm::Disassemble(p, source).find("; 2") == std::string::npos);
}

TEST_CASE("disasm: texture slots are listed with their options", "[vm][disasm]") {
    vm::Program p = WithCode({Instr{Op::Texture2, 0, 0, 0, 0}});
    auto slots = std::make_shared<vm::TextureSlots>(2);
    (*slots)[0].path = "bumps.tx";
    (*slots)[1].path = "/maps/rock.exr";
    texture::LookupOptions& o = (*slots)[1].options;
    o.channel = 2;
    o.swrap = texture::Wrap::Clamp;
    o.twrap = texture::Wrap::Black;
    o.filter = texture::Filter::Gaussian;
    o.sblur = 0.125;
    o.tblur = 0.25;
    o.fill = 1;
    (*slots)[1].map = texture::TextureMap::FromPixels(1, 1, 1, {0.5f});
    p.textures = slots;
    const std::string listing = vm::Disassemble(p, "");
    CHECK(listing.find("; texture 0 = \"bumps.tx\" channel 0, wrap periodic periodic, filter box, blur 0 0, "
                       "fill 0 (no map: the fill)\n") != std::string::npos);
    CHECK(listing.find("; texture 1 = \"/maps/rock.exr\" channel 2, wrap clamp black, filter gaussian, "
                       "blur 0.125 0.25, fill 1\n") != std::string::npos);
    CHECK(listing.find("   0  Texture2 r0, r0, r0  [texture 0]\n") != std::string::npos);
}

TEST_CASE("the disassembly shows opcodes, constants and source lines", "[vm][disasm]") {
    compiler::CompiledShader s = test::CompileOrThrow("displacement t() {\n  P += 0.25 * sin(u) * N;\n}\n");
    std::string listing = vm::Disassemble(s.bound, s.sourceText);
    CHECK(listing.find("; 2: P += 0.25 * sin(u) * N;") != std::string::npos);
    CHECK(listing.find("Sin") != std::string::npos);
    CHECK(listing.find("(0.25)") != std::string::npos);
}
