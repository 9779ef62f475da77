// compiler/opcode_map.cpp: the rows of the table (see the header).
#include "compiler/opcode_map.h"

#include <array>

namespace affray::compiler {

namespace {

using F = OperandForm;
using vm::Op;

constexpr OpcodeRow kRows[] = {
    {IrOp::Neg, 1, F::RR, Op::Neg},         {IrOp::Sqr, 1, F::RR, Op::Sqr},
    {IrOp::Sqrt, 1, F::RR, Op::Sqrt},       {IrOp::Exp, 1, F::RR, Op::Exp},
    {IrOp::Log, 1, F::RR, Op::Log},         {IrOp::Sin, 1, F::RR, Op::Sin},
    {IrOp::Cos, 1, F::RR, Op::Cos},         {IrOp::Abs, 1, F::RR, Op::Abs},
    {IrOp::Sign, 1, F::RR, Op::Sign},       {IrOp::DerivU, 1, F::RR, Op::DerivU},
    {IrOp::DerivV, 1, F::RR, Op::DerivV},   {IrOp::Floor, 1, F::RR, Op::Floor},
    {IrOp::Ceil, 1, F::RR, Op::Ceil},       {IrOp::Round, 1, F::RR, Op::Round},
    {IrOp::Asin, 1, F::RR, Op::Asin},       {IrOp::Acos, 1, F::RR, Op::Acos},
    {IrOp::Atan, 1, F::RR, Op::Atan},       {IrOp::Not, 1, F::RR, Op::Not},
    {IrOp::Add, 2, F::RR, Op::AddRR},       {IrOp::Add, 2, F::RK, Op::AddRK},
    {IrOp::Sub, 2, F::RR, Op::SubRR},       {IrOp::Sub, 2, F::RK, Op::SubRK},
    {IrOp::Sub, 2, F::KR, Op::SubKR},       {IrOp::Mul, 2, F::RR, Op::MulRR},
    {IrOp::Mul, 2, F::RK, Op::MulRK},       {IrOp::Div, 2, F::RR, Op::DivRR},
    {IrOp::Div, 2, F::RK, Op::DivRK},       {IrOp::Div, 2, F::KR, Op::DivKR},
    {IrOp::Pow, 2, F::RR, Op::PowRR},       {IrOp::Pow, 2, F::RK, Op::PowRK},
    {IrOp::Min, 2, F::RR, Op::MinRR},       {IrOp::Min, 2, F::RK, Op::MinRK},
    {IrOp::Max, 2, F::RR, Op::MaxRR},       {IrOp::Max, 2, F::RK, Op::MaxRK},
    {IrOp::Atan2, 2, F::RR, Op::Atan2RR},   {IrOp::Lt, 2, F::RR, Op::LtRR},
    {IrOp::Lt, 2, F::RK, Op::LtRK},         {IrOp::Lt, 2, F::KR, Op::LtKR},
    {IrOp::Le, 2, F::RR, Op::LeRR},         {IrOp::Le, 2, F::RK, Op::LeRK},
    {IrOp::Le, 2, F::KR, Op::LeKR},         {IrOp::Eq, 2, F::RR, Op::EqRR},
    {IrOp::Eq, 2, F::RK, Op::EqRK},         {IrOp::Ne, 2, F::RR, Op::NeRR},
    {IrOp::Ne, 2, F::RK, Op::NeRK},         {IrOp::And, 2, F::RR, Op::AndRR},
    {IrOp::Or, 2, F::RR, Op::OrRR},         {IrOp::Select, 3, F::RR, Op::Select},
    {IrOp::Noise, 1, F::RR, Op::Noise1},    {IrOp::Noise, 2, F::RR, Op::Noise2},
    {IrOp::Noise, 3, F::RR, Op::Noise3},    {IrOp::Noise, 4, F::RR, Op::Noise4},
    {IrOp::PNoise, 2, F::RR, Op::PNoise1},  {IrOp::PNoise, 4, F::RR, Op::PNoise2},
    {IrOp::PNoise, 6, F::RR, Op::PNoise3},  {IrOp::PNoise, 8, F::RR, Op::PNoise4},
    {IrOp::CellNoise, 1, F::RR, Op::CellNoise1}, {IrOp::CellNoise, 2, F::RR, Op::CellNoise2},
    {IrOp::CellNoise, 3, F::RR, Op::CellNoise3}, {IrOp::CellNoise, 4, F::RR, Op::CellNoise4},
};

// Every opcode but LoadK, Move and Ext implements exactly one row.
constexpr int kMappedOpcodes = vm::kOpCount - 3;
static_assert(std::size(kRows) == kMappedOpcodes, "add a row for each new opcode");

}  // namespace

std::optional<vm::Op> OpcodeFor(IrOp op, int count, OperandForm form) {
    for (const OpcodeRow& row : kRows)
        if (row.ir == op && row.count == count && row.form == form) return row.vm;
    return std::nullopt;
}

const OpcodeRow* RowOf(vm::Op op) {
    static const std::array<const OpcodeRow*, vm::kOpCount> kByOpcode = [] {
        std::array<const OpcodeRow*, vm::kOpCount> table{};
        for (const OpcodeRow& row : kRows) table[static_cast<int>(row.vm)] = &row;
        return table;
    }();
    return kByOpcode[static_cast<int>(op)];
}

}  // namespace affray::compiler
