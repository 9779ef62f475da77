// tests/compiler/ir_test.cpp: the value graph's builder (compiler/ir.*): each distinct (operation,
// operands, channel) is one node, asked for again it is the same id; a commutative operation's
// operands are put in one order, so a*b and b*a share; leaves (constants by their bits, globals
// and parameters by index and component) are shared too and found again by FindLeaf; which nodes
// are always 0 or 1; and the count of requested operations, which sharing and folding do not
// change. The folding rules themselves are tests/compiler/fold_test.cpp's.
#include <catch2/catch.hpp>

#include <cmath>

#include "compiler/ir.h"

using namespace affray;
using compiler::IrBuilder;
using compiler::IrOp;
using compiler::ValueId;

TEST_CASE("ir: leaves are made once, constants told apart by their bits", "[compiler][ir]") {
    IrBuilder ir;
    const ValueId u = ir.Global(vm::Global::u, 0);
    CHECK(ir.Global(vm::Global::u, 0) == u);
    const ValueId py = ir.Global(vm::Global::P, 1);
    CHECK(py != u);
    CHECK(ir.Global(vm::Global::P, 2) != py);
    const ValueId param = ir.Param(0, 0);
    CHECK(param != u);
    CHECK(ir.Param(0, 0) == param);

    const ValueId zero = ir.Const(0.0), minusZero = ir.Const(-0.0), half = ir.Const(0.5);
    CHECK(zero != minusZero);
    CHECK(ir.Const(0.0) == zero);
    CHECK(ir.Const(0.25 + 0.25) == half);
    const ValueId nan = ir.Const(NAN);
    CHECK(ir.Const(NAN) == nan);  // the same bits, though NaN != NaN
    CHECK(ir.size() == 8);

    CHECK(ir.node(py).op == IrOp::Global);
    CHECK(ir.node(py).in[0] == uint32_t(vm::Global::P));
    CHECK(ir.node(py).in[1] == 1);
    CHECK(ir.ConstValue(half) == 0.5);
    CHECK_FALSE(ir.ConstValue(u).has_value());
    CHECK(std::signbit(*ir.ConstValue(minusZero)));

    CHECK(ir.FindLeaf(IrOp::Global, uint32_t(vm::Global::P), 1) == py);
    CHECK(ir.FindLeaf(IrOp::Param, 0, 0) == param);
    CHECK(ir.FindLeaf(IrOp::Global, uint32_t(vm::Global::v), 0) == compiler::kNoValue);
    CHECK(ir.FindLeaf(IrOp::Param, 1, 0) == compiler::kNoValue);
}

TEST_CASE("ir: an operation asked for again is the same node, and commutative operands are ordered", "[compiler][ir]") {
    IrBuilder ir;
    const ValueId u = ir.Global(vm::Global::u, 0);
    const ValueId v = ir.Global(vm::Global::v, 0);
    const ValueId sinU = ir.Unary(IrOp::Sin, u, 1);
    CHECK(ir.Unary(IrOp::Sin, u, 9) == sinU);
    CHECK(ir.node(sinU).line == 1);  // the line that first asked for it
    CHECK(ir.Unary(IrOp::Cos, u, 1) != sinU);

    const ValueId uv = ir.Binary(IrOp::Mul, u, v, 2);
    CHECK(ir.Binary(IrOp::Mul, v, u, 2) == uv);
    CHECK(ir.node(uv).in[0] == u);  // the lower id first
    CHECK(ir.node(uv).in[1] == v);
    CHECK(ir.Binary(IrOp::Add, v, u, 2) == ir.Binary(IrOp::Add, u, v, 2));
    // Not commutative: u - v and v - u are two nodes, each with its operands as given.
    const ValueId uMinusV = ir.Binary(IrOp::Sub, u, v, 3), vMinusU = ir.Binary(IrOp::Sub, v, u, 3);
    CHECK(uMinusV != vMinusU);
    CHECK(ir.node(vMinusU).in[0] == v);
    CHECK(ir.Binary(IrOp::Atan2, u, v, 3) != ir.Binary(IrOp::Atan2, v, u, 3));

    // Noise on another channel is another value.
    const ValueId n0 = ir.Call(IrOp::Noise, {u, v}, 0, 4);
    CHECK(ir.Call(IrOp::Noise, {u, v}, 0, 4) == n0);
    CHECK(ir.Call(IrOp::Noise, {u, v}, 1, 4) != n0);
    CHECK(ir.Call(IrOp::Noise, {u}, 0, 4) != n0);
    CHECK(ir.node(n0).count == 2);

    const ValueId sel = ir.Select(ir.Binary(IrOp::Lt, u, v, 5), u, v, 5);
    CHECK(ir.Select(ir.Binary(IrOp::Lt, u, v, 6), u, v, 6) == sel);
    CHECK(ir.node(sel).op == IrOp::Select);
    CHECK(ir.node(sel).count == 3);
}

TEST_CASE("ir: constant operands fold on creation into constants", "[compiler][ir]") {
    IrBuilder ir;
    const ValueId sum = ir.Binary(IrOp::Add, ir.Const(1), ir.Const(2), 1);
    CHECK(ir.ConstValue(sum) == 3);
    CHECK(sum == ir.Const(3));
    const ValueId u = ir.Global(vm::Global::u, 0);
    CHECK(ir.Binary(IrOp::Mul, u, ir.Const(1), 1) == u);
    CHECK(ir.Binary(IrOp::Mul, ir.Const(1), u, 1) == u);
}

TEST_CASE("ir: comparisons, logic and Selects of 0 and 1 are booleans", "[compiler][ir]") {
    IrBuilder ir;
    const ValueId u = ir.Global(vm::Global::u, 0);
    const ValueId v = ir.Global(vm::Global::v, 0);
    CHECK_FALSE(ir.IsBoolean(u));
    CHECK(ir.IsBoolean(ir.Const(0)));
    CHECK(ir.IsBoolean(ir.Const(1)));
    CHECK_FALSE(ir.IsBoolean(ir.Const(0.5)));
    const ValueId less = ir.Binary(IrOp::Lt, u, v, 1);
    CHECK(ir.IsBoolean(less));
    CHECK(ir.IsBoolean(ir.Binary(IrOp::Eq, u, v, 1)));
    CHECK(ir.IsBoolean(ir.Unary(IrOp::Not, u, 1)));
    CHECK(ir.IsBoolean(ir.Binary(IrOp::And, u, v, 1)));
    CHECK_FALSE(ir.IsBoolean(ir.Binary(IrOp::Add, u, v, 1)));
    CHECK_FALSE(ir.IsBoolean(ir.Unary(IrOp::Floor, u, 1)));
    const ValueId other = ir.Binary(IrOp::Le, v, u, 1);
    CHECK(ir.IsBoolean(ir.Select(u, less, other, 1)));        // either arm 0 or 1
    CHECK_FALSE(ir.IsBoolean(ir.Select(less, u, other, 1)));  // an arm that is not
}

TEST_CASE("ir: requested operations count every request, shared or folded, and can be forgotten", "[compiler][ir]") {
    IrBuilder ir;
    const ValueId u = ir.Global(vm::Global::u, 0);
    ir.Const(2);
    CHECK(ir.requestedOps() == 0);  // leaves are no operations
    const ValueId sinU = ir.Unary(IrOp::Sin, u, 1);
    ir.Unary(IrOp::Sin, u, 1);                          // shared
    ir.Binary(IrOp::Add, ir.Const(1), ir.Const(2), 1);  // folded
    ir.Binary(IrOp::Mul, sinU, ir.Const(1), 1);         // folded to sin(u)
    CHECK(ir.requestedOps() == 4);
    const size_t nodes = ir.size();
    const int before = ir.requestedOps();
    ir.Unary(IrOp::Cos, u, 1);
    ir.Unary(IrOp::Exp, u, 1);
    CHECK(ir.requestedOps() == before + 2);
    ir.ForgetRequestsSince(before);
    CHECK(ir.requestedOps() == before);
    CHECK(ir.size() == nodes + 2);  // the nodes stay
}

TEST_CASE("ir: names and operand counts come from the opcode table", "[compiler][ir]") {
    CHECK(std::string(compiler::ToString(IrOp::Const)) == "Const");
    CHECK(std::string(compiler::ToString(IrOp::Global)) == "Global");
    CHECK(std::string(compiler::ToString(IrOp::Param)) == "Param");
    CHECK(std::string(compiler::ToString(IrOp::Sin)) == "Sin");
    CHECK(std::string(compiler::ToString(IrOp::Atan2)) == "Atan2");
    CHECK(compiler::Arity(IrOp::Const) == 0);
    CHECK(compiler::Arity(IrOp::Sin) == 1);
    CHECK(compiler::Arity(IrOp::Sub) == 2);
    CHECK(compiler::Arity(IrOp::Select) == 3);
    CHECK(compiler::Arity(IrOp::Noise) == -1);
    CHECK(compiler::IsCommutative(IrOp::Mul));
    CHECK_FALSE(compiler::IsCommutative(IrOp::Div));
    CHECK(compiler::IsBooleanOp(IrOp::Ne));
    CHECK_FALSE(compiler::IsBooleanOp(IrOp::Min));
}
