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

//  X(name, operand count: 0 a leaf, 1, 2, 3, or -1 a variable number)
#define AFFRAY_IR_OPS(X)                                                                         \
    X(Const, 0) X(Global, 0) X(Param, 0)                                                         \
    X(Neg, 1) X(Sqr, 1) X(Sqrt, 1) X(Exp, 1) X(Log, 1) X(Sin, 1) X(Cos, 1) X(Abs, 1) X(Sign, 1)  \
    X(DerivU, 1) X(DerivV, 1) X(Floor, 1) X(Ceil, 1) X(Round, 1) X(Asin, 1) X(Acos, 1)           \
    X(Atan, 1) X(Not, 1)                                                                         \
    X(Add, 2) X(Sub, 2) X(Mul, 2) X(Div, 2) X(Pow, 2) X(Min, 2) X(Max, 2) X(Atan2, 2) X(Lt, 2)   \
    X(Le, 2) X(Eq, 2) X(Ne, 2) X(And, 2) X(Or, 2)                                                \
    X(Select, 3)                                                                                 \
    X(Noise, -1) X(PNoise, -1) X(CellNoise, -1)

enum class IrOp : uint8_t {
#define AFFRAY_IR_ENUM(name, arity) name,
    AFFRAY_IR_OPS(AFFRAY_IR_ENUM)
#undef AFFRAY_IR_ENUM
};
const char* ToString(IrOp op);
/// 0 for leaves, else the operand count; -1 for the noise functions (1 to 8 operands).
int Arity(IrOp op);
inline bool IsUnary(IrOp op) { return Arity(op) == 1; }
inline bool IsBinary(IrOp op) { return Arity(op) == 2; }
/// a op b == b op a, so the builder orders the operands canonically.
bool IsCommutative(IrOp op);
/// Gives only 1 or 0 (comparisons and logic).
bool IsBooleanOp(IrOp op);

using ValueId = uint32_t;
inline constexpr ValueId kNoValue = 0xffffffffu;
inline constexpr int kMaxIrOperands = 8;

struct IrNode {
    IrOp op = IrOp::Const;
    uint8_t count = 0;    // operands in `in`
    uint8_t channel = 0;  // the noise functions' seed
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
    /// A noise function of `operands` (coordinates, then periods for PNoise) on `channel`.
    ValueId Noise(IrOp op, const std::vector<ValueId>& operands, int channel, int line);

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
inline bool IsParameterLoopPoison(double k) { return std::bit_cast<uint64_t>(k) == std::bit_cast<uint64_t>(kParameterLoopPoison); }

/// Tries the rewrite rules of compiler/fold.cpp on node `n` (operands set, not yet created);
/// returns the folded value or nothing.
std::optional<ValueId> Fold(IrBuilder& ir, const IrNode& n);

}  // namespace affray::compiler
