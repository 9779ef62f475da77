// compiler/ir.cpp: building the value graph with sharing and folding on creation.
#include "compiler/ir.h"

#include <algorithm>
#include <bit>

namespace affray::compiler {

const char* ToString(IrOp op) {
    static constexpr const char* kLeaves[] = {"Const", "Global", "Param"};
    const int i = static_cast<int>(op);
    return i < kIrLeaves ? kLeaves[i] : vm::Info(OperationOf(op)).name;
}

int Arity(IrOp op) { return static_cast<int>(op) < kIrLeaves ? 0 : vm::Info(OperationOf(op)).operands; }

size_t IrBuilder::KeyHash::operator()(const Key& k) const {
    uint64_t h =
        (static_cast<uint64_t>(k.op) << 16 | static_cast<uint64_t>(k.count) << 8 | k.channel) * 0x9E3779B97F4A7C15ull;
    for (int i = 0; i < k.count || (i < 2 && k.count == 0); ++i)
        h ^= k.in[i] + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= k.kBits + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    return static_cast<size_t>(h);
}

ValueId IrBuilder::Intern(const IrNode& n) {
    Key key{n.op, n.count, n.channel, n.in, std::bit_cast<uint64_t>(n.k)};
    auto [it, inserted] = m_index.try_emplace(key, static_cast<ValueId>(m_nodes.size()));
    if (inserted) {
        m_nodes.push_back(n);
        IrNode& added = m_nodes.back();
        added.boolean = n.op == IrOp::Const    ? (n.k == 0.0 || n.k == 1.0)
                        : n.op == IrOp::Select ? m_nodes[n.in[1]].boolean && m_nodes[n.in[2]].boolean
                                               : IsBooleanOp(n.op);
    }
    return it->second;
}

ValueId IrBuilder::Create(IrNode n) {
    ++m_requested;
    // Commutative operations get a canonical operand order, so a*b and b*a share one node.
    if (IsCommutative(n.op) && n.in[0] > n.in[1]) std::swap(n.in[0], n.in[1]);
    if (auto folded = Fold(*this, n)) return *folded;
    return Intern(n);
}

ValueId IrBuilder::Const(double k) {
    // -0.0 and 0.0 are distinct keys (their bits differ), which is right: 1/-0 != 1/0.
    IrNode n;
    n.k = k;
    return Intern(n);
}

ValueId IrBuilder::Global(vm::Global g, int component) {
    IrNode n;
    n.op = IrOp::Global;
    n.in[0] = static_cast<uint32_t>(g);
    n.in[1] = static_cast<uint32_t>(component);
    return Intern(n);
}

ValueId IrBuilder::Param(int index, int component) {
    IrNode n;
    n.op = IrOp::Param;
    n.in[0] = static_cast<uint32_t>(index);
    n.in[1] = static_cast<uint32_t>(component);
    return Intern(n);
}

ValueId IrBuilder::Unary(IrOp op, ValueId a, int line) {
    IrNode n;
    n.op = op;
    n.count = 1;
    n.in[0] = a;
    n.line = line;
    return Create(n);
}

ValueId IrBuilder::Binary(IrOp op, ValueId a, ValueId b, int line) {
    IrNode n;
    n.op = op;
    n.count = 2;
    n.in[0] = a;
    n.in[1] = b;
    n.line = line;
    return Create(n);
}

ValueId IrBuilder::Select(ValueId c, ValueId a, ValueId b, int line) {
    IrNode n;
    n.op = IrOp::Select;
    n.count = 3;
    n.in = {c, a, b};
    n.line = line;
    return Create(n);
}

ValueId IrBuilder::Call(IrOp op, const std::vector<ValueId>& operands, int channel, int line) {
    IrNode n;
    n.op = op;
    n.count = static_cast<uint8_t>(operands.size());
    n.channel = static_cast<uint8_t>(channel);
    std::copy(operands.begin(), operands.end(), n.in.begin());
    n.line = line;
    return Create(n);
}

ValueId IrBuilder::FindLeaf(IrOp op, uint32_t a, uint32_t b) const {
    std::array<uint32_t, kMaxIrOperands> in{};
    in[0] = a;
    in[1] = b;
    auto it = m_index.find(Key{op, 0, 0, in, 0});
    return it == m_index.end() ? kNoValue : it->second;
}

std::optional<double> IrBuilder::ConstValue(ValueId v) const {
    if (m_nodes[v].op == IrOp::Const) return m_nodes[v].k;
    return std::nullopt;
}

}  // namespace affray::compiler
