// compiler/ir.h: the compiler's intermediate form, a graph of scalar values.
// Lowering turns every triple operation into scalar nodes; a node is created once per distinct
// (op, operands) pair (hash-consing = global value numbering on straight-line code), and folds
// on creation when its operands are constants (compiler/fold.cpp holds the rules). Variables are
// not storage: assigning a variable just rebinds its name to another node, so the graph is in
// SSA form and dead code is whatever the outputs do not reach.
#pragma once

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "vm/program.h"

namespace affray::compiler {

enum class IrOp : uint8_t {
    Const,   // k
    Global,  // a = vm::Global index, b = component
    Param,   // a = parameter index, b = component (a parameter not bound to a constant)
    Neg, Sqr, Sqrt, Exp, Log, Sin, Cos, Abs, Sign, DerivU, DerivV,  // unary on a
    Add, Sub, Mul, Div, Pow,  // binary on a, b
};
const char* ToString(IrOp op);
inline bool IsUnary(IrOp op) { return op >= IrOp::Neg && op <= IrOp::DerivV; }
inline bool IsBinary(IrOp op) { return op >= IrOp::Add; }

using ValueId = uint32_t;
inline constexpr ValueId kNoValue = 0xffffffffu;

struct IrNode {
    IrOp op = IrOp::Const;
    uint32_t a = 0, b = 0;
    double k = 0;
    int line = 0;  // source line that first asked for this node
};

class IrBuilder {
  public:
    ValueId Const(double k);
    ValueId Global(vm::Global g, int component);
    ValueId Param(int index, int component);
    ValueId Unary(IrOp op, ValueId a, int line);
    ValueId Binary(IrOp op, ValueId a, ValueId b, int line);

    const IrNode& node(ValueId v) const { return m_nodes[v]; }
    size_t size() const { return m_nodes.size(); }
    /// The existing node (op, a, b) with k = 0, or kNoValue (e.g. to ask whether a global was read).
    ValueId Find(IrOp op, uint32_t a, uint32_t b) const;
    /// The constant value of `v`, if it is a constant.
    std::optional<double> ConstValue(ValueId v) const;
    /// How many operations lowering asked for, before folding and sharing: the instruction count
    /// of a compiler that optimises nothing.
    int requestedOps() const { return m_requested; }

  private:
    ValueId Intern(const IrNode& n);

    struct Key {
        IrOp op;
        uint32_t a, b;
        uint64_t kBits;
        bool operator==(const Key&) const = default;
    };
    struct KeyHash {
        size_t operator()(const Key& k) const;
    };
    std::vector<IrNode> m_nodes;
    std::unordered_map<Key, ValueId, KeyHash> m_index;
    int m_requested = 0;
};

/// Tries the rewrite rules of compiler/fold.cpp on `op(a, b)`; returns the folded value or nothing.
std::optional<ValueId> Fold(IrBuilder& ir, IrOp op, ValueId a, ValueId b, int line);

}  // namespace affray::compiler
