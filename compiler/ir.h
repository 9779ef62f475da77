// compiler/ir.h: the compiler's intermediate form, a graph of scalar values.
// Lowering turns every triple operation into scalar nodes; a node is created once per distinct
// (op, operands) pair (hash-consing = global value numbering on straight-line code), and folds
// on creation when its operands are constants (compiler/fold.cpp holds the rules). Variables are
// not storage: assigning a variable just rebinds its name to another node, so the graph is in
// SSA form and dead code is whatever the outputs do not reach. Control flow is gone by the time
// it gets here: a branch is a Select of the values its arms computed, a loop is unrolled
// (compiler/lower.cpp), so the graph stays straight-line code that every number type can run,
// bounds included. Booleans are numbers: 1 or 0 (comparisons, And, Or, Not).
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "vm/program.h"

namespace affray::compiler {

// The IR operations: three leaves (a constant, a shader global, a parameter), then the VM's
// operations in their order (vm/opcodes.h, AFFRAY_OPERATIONS), whose facts the compiler reads from
// that one table.
enum class IrOp : uint8_t {
    Const,
    Global,
    Param,
#define AFFRAY_IR_ENUM(name, operands, flags, rsl) name,
    AFFRAY_OPERATIONS(AFFRAY_IR_ENUM)
#undef AFFRAY_IR_ENUM
};
inline constexpr int kIrLeaves = 3;
/// The VM operation of an IR operation (None for the leaves), and back.
constexpr vm::Operation OperationOf(IrOp op) {
    return static_cast<int>(op) < kIrLeaves ? vm::Operation::None
                                            : static_cast<vm::Operation>(static_cast<int>(op) - kIrLeaves + 1);
}
constexpr IrOp IrOpOf(vm::Operation f) { return static_cast<IrOp>(static_cast<int>(f) - 1 + kIrLeaves); }
static_assert(OperationOf(IrOp::Neg) == vm::Operation::Neg && OperationOf(IrOp::CellNoise) == vm::Operation::CellNoise);

const char* ToString(IrOp op);
/// 0 for leaves, else the operand count; -1 for the noise and texture functions (1 to 8 operands).
int Arity(IrOp op);
inline bool IsUnary(IrOp op) { return Arity(op) == 1; }
inline bool IsBinary(IrOp op) { return Arity(op) == 2; }
/// a op b == b op a, so the builder orders the operands canonically.
inline bool IsCommutative(IrOp op) { return vm::Has(OperationOf(op), vm::kCommutative); }
/// Gives only 1 or 0 (comparisons and logic).
inline bool IsBooleanOp(IrOp op) { return vm::Has(OperationOf(op), vm::kTruth); }

using ValueId = uint32_t;
inline constexpr ValueId kNoValue = 0xffffffffu;
inline constexpr int kMaxIrOperands = 8;

struct IrNode {
    IrOp op = IrOp::Const;
    uint8_t count = 0;    // operands in `in`
    uint8_t channel = 0;  // the noise functions' seed, the texture functions' slot
    // Operands (value ids). Global: in[0] = vm::Global index, in[1] = component; Param:
    // in[0] = parameter index, in[1] = component.
    std::array<uint32_t, kMaxIrOperands> in{};
    double k = 0;
    int line = 0;          // source line that first asked for this node
    bool boolean = false;  // always 1 or 0 (set by the builder)
};

class IrBuilder {
  public:
    ValueId Const(double k);
    ValueId Global(vm::Global g, int component);
    ValueId Param(int index, int component);
    ValueId Unary(IrOp op, ValueId a, int line);
    ValueId Binary(IrOp op, ValueId a, ValueId b, int line);
    /// c != 0 ? a : b.
    ValueId Select(ValueId c, ValueId a, ValueId b, int line);
    /// An operation of up to kMaxIrOperands operands with a channel: a noise function of
    /// `operands` (coordinates, then periods for PNoise) on noise channel `channel`, or a texture
    /// lookup of (s, t) or four corners through texture slot `channel`.
    ValueId Call(IrOp op, const std::vector<ValueId>& operands, int channel, int line);

    const IrNode& node(ValueId v) const { return m_nodes[v]; }
    size_t size() const { return m_nodes.size(); }
    /// The existing leaf (Global or Param) with indices (a, b), or kNoValue.
    ValueId FindLeaf(IrOp op, uint32_t a, uint32_t b) const;
    /// The constant value of `v`, if it is a constant.
    std::optional<double> ConstValue(ValueId v) const;
    /// Always 1 or 0.
    bool IsBoolean(ValueId v) const { return m_nodes[v].boolean; }
    /// How many operations lowering asked for, before folding and sharing: the instruction count
    /// of a compiler that optimises nothing.
    int requestedOps() const { return m_requested; }
    /// Forgets the requests made since requestedOps() was `count` (a check that keeps nothing).
    void ForgetRequestsSince(int count) { m_requested = count; }

    /// The node `n` (an operation with its operands set): folded, or shared, or new.
    ValueId Create(IrNode n);

  private:
    ValueId Intern(const IrNode& n);

    struct Key {
        IrOp op;
        uint8_t count, channel;
        std::array<uint32_t, kMaxIrOperands> in;
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

/// The value of paths still running in a loop past its unrolling budget when the loop's
/// condition depends on a parameter: a quiet NaN with a payload of its own, so that specialising
/// such a generic program for parameter values that need more iterations is an error, not NaN.
inline const double kParameterLoopPoison = std::bit_cast<double>(uint64_t{0x7ff8'0000'0afa'1009});
inline bool IsParameterLoopPoison(double k) {
    return std::bit_cast<uint64_t>(k) == std::bit_cast<uint64_t>(kParameterLoopPoison);
}

/// Tries the rewrite rules of compiler/fold.cpp on node `n` (operands set, not yet created);
/// returns the folded value or nothing.
std::optional<ValueId> Fold(IrBuilder& ir, const IrNode& n);

}  // namespace affray::compiler
