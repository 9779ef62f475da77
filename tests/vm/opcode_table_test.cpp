// tests/vm/opcode_table_test.cpp: the one opcode table (vm/opcodes.h) and what is derived from it:
// docs/opcodes.md lists it as `affray opcodes` prints it, the constant forms the pruner uses are
// the hand-checked ones, and the compiler's map lifts every opcode back to itself.
#include <catch2/catch.hpp>

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
        CHECK(compiler::OperationOf(row->ir) == vm::OperationOf(op));
        CHECK(compiler::OpcodeFor(row->ir, row->count, row->form) == op);
        CHECK(row->count == vm::OperandCount(op));
    }
    CHECK(rows == vm::kOpCount - 3);  // all but LoadK, Move and Ext
}
