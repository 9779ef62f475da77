// compiler/ir.cpp: building the value graph with sharing and folding on creation.
#include "compiler/ir.h"

#include <bit>

namespace affray::compiler {

const char* ToString(IrOp op) {
    static const char* const kNames[] = {"const", "global", "param", "neg",  "sqr", "sqrt", "exp",
                                         "log",   "sin",    "cos",  "abs", "sign", "du",
                                         "dv",    "add",    "sub",  "mul", "div",  "pow"};
    return kNames[static_cast<int>(op)];
}

size_t IrBuilder::KeyHash::operator()(const Key& k) const {
    uint64_t h = static_cast<uint64_t>(k.op) * 0x9E3779B97F4A7C15ull;
    h ^= (static_cast<uint64_t>(k.a) << 32 | k.b) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= k.kBits + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    return static_cast<size_t>(h);
}

ValueId IrBuilder::Intern(const IrNode& n) {
    Key key{n.op, n.a, n.b, std::bit_cast<uint64_t>(n.k)};
    auto [it, inserted] = m_index.try_emplace(key, static_cast<ValueId>(m_nodes.size()));
    if (inserted) m_nodes.push_back(n);
    return it->second;
}

ValueId IrBuilder::Const(double k) {
    // -0.0 and 0.0 are distinct keys (their bits differ), which is right: 1/-0 != 1/0.
    return Intern({IrOp::Const, 0, 0, k, 0});
}

ValueId IrBuilder::Global(vm::Global g, int component) {
    return Intern({IrOp::Global, static_cast<uint32_t>(g), static_cast<uint32_t>(component), 0, 0});
}

ValueId IrBuilder::Param(int index, int component) {
    return Intern({IrOp::Param, static_cast<uint32_t>(index), static_cast<uint32_t>(component), 0, 0});
}

ValueId IrBuilder::Unary(IrOp op, ValueId a, int line) {
    ++m_requested;
    if (auto folded = Fold(*this, op, a, 0, line)) return *folded;
    return Intern({op, a, 0, 0, line});
}

ValueId IrBuilder::Binary(IrOp op, ValueId a, ValueId b, int line) {
    ++m_requested;
    // Commutative operations get a canonical operand order, so a*b and b*a share one node.
    if ((op == IrOp::Add || op == IrOp::Mul) && a > b) std::swap(a, b);
    if (auto folded = Fold(*this, op, a, b, line)) return *folded;
    return Intern({op, a, b, 0, line});
}

ValueId IrBuilder::Find(IrOp op, uint32_t a, uint32_t b) const {
    auto it = m_index.find(Key{op, a, b, 0});
    return it == m_index.end() ? kNoValue : it->second;
}

std::optional<double> IrBuilder::ConstValue(ValueId v) const {
    if (m_nodes[v].op == IrOp::Const) return m_nodes[v].k;
    return std::nullopt;
}

}  // namespace affray::compiler
