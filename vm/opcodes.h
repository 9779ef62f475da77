// vm/opcodes.h: THE list of opcodes. Nothing else in affray enumerates them: the enum, the names,
// the operand formats used by the verifier and the disassembler are all generated from this one
// X-macro. To add an opcode: append a line at the end with the next number (never renumber:
// compiled programs store these numbers), then handle it in Interpreter<T>::Run.
//
// Encoding: every instruction is 8 bytes,
//
//   bits  0..7   op      (MAXARG_OP = 255)
//   bits  8..15  flags   (the noise functions' seed, which picks an independent channel; the
//                        texture functions' slot in Program::textures; the light slot of
//                        Light, vm/lights.h; else 0)
//   bits 16..31  A       destination register
//   bits 32..47  B       first operand: a register R[B] or a constant K[B]
//   bits 48..63  C       second operand: a register R[C] or a constant K[C]
//
// Registers and constants are indexed by 16 bits (kMaxRegisters, kMaxConstants). All registers
// hold one scalar of the interpreter's number type; points, vectors and normals live in three
// registers because the compiler lowers every triple operation to scalar operations.
//
// Format letters: 'w' a register written, 'r' a register read, 'k' a constant read, '-' unused.
// The name says where the operands come from: AddRK is R[B] + K[C], SubKR is K[B] - R[C].
// An operation with more operands than B and C (Select, the noise functions) is followed by one
// or two Ext words whose A, B and C are its further operands (format letters 4..6 and 7..9, as
// the operand list R[D], R[E], ...): the format's length says how many words an instruction takes.
// Booleans are numbers: comparisons give 1 or 0 (a bound type: [0, 1] when undecided over the
// region) and every truth test is "not 0".
#pragma once

#include <cstdint>

namespace affray::vm {

/// What an operation is, beyond its operands (OperationInfo::flags).
enum OperationFlag : uint8_t {
    /// Constant operands give a constant result, computed at compile time by running the opcode
    /// in the scalar VM (compiler/fold.cpp): every operation but the derivatives.
    kFoldable = 1,
    /// The scalar result is exactly 1.0 or +0.0 (comparisons and logic), so a bound that is a
    /// point stands for that value, zero included.
    kTruth = 2,
    /// op(a, b) == op(b, a) as values: the compiler orders the operands canonically to share
    /// nodes.
    kCommutative = 4,
    /// op(a, b) and op(b, a) are the same double bit for bit (IEEE + * == !=; not fmin or fmax,
    /// which differ on signed zeros): an instruction may swap its operands to take a constant.
    kSwapsExactly = 8,
    /// Reads the derivatives of its operand (a number type without them gives "unknown").
    kDerivative = 16,
    /// The scalar result jumps where an operand crosses a threshold (a comparison's, an integer
    /// for a rounding, 0 for sign, a cell's face, a Select's condition): its derivative rule (zero,
    /// or the picked operand's) holds between the jumps only. Over a region where such an
    /// instruction is undecided, derivative bounds do not bound how far the value moves
    /// (vm/prune.h: JumpsDecided).
    kJumps = 32,
    /// Its derivative bounds over a region hold point by point only, never as a bound of how far
    /// the value moves across the region: atan2's branch cut, a texture's filtering.
    kPointwiseSlope = 64,
};

// The operations of the VM: each is implemented by one opcode per operand form (below). The
// compiler's IR operations are these plus its leaves (compiler/ir.h), and every fact a consumer
// needs about an operation is a column here.
//  X(name, operands (-1: varies, the noise and texture functions), flags, RSL spelling)
// Texture is not foldable: its value depends on a file, read when the program is made; Light
// neither: the renderer answers it at each shaded point (vm/lights.h), nor Trace.
#define AFFRAY_OPERATIONS(X)                                                       \
    X(Neg, 1, kFoldable, "-x")                                                     \
    X(Sqr, 1, kFoldable, "x * x")                                                  \
    X(Sqrt, 1, kFoldable, "sqrt(x)")                                               \
    X(Exp, 1, kFoldable, "exp(x)")                                                 \
    X(Log, 1, kFoldable, "log(x)")                                                 \
    X(Sin, 1, kFoldable, "sin(x)")                                                 \
    X(Cos, 1, kFoldable, "cos(x)")                                                 \
    X(Tan, 1, kFoldable, "tan(x)")                                                 \
    X(Abs, 1, kFoldable, "abs(x)")                                                 \
    X(Sign, 1, kFoldable | kJumps, "sign(x)")                                      \
    X(DerivU, 1, kDerivative, "Du(x)")                                             \
    X(DerivV, 1, kDerivative, "Dv(x)")                                             \
    X(Floor, 1, kFoldable | kJumps, "floor(x)")                                    \
    X(Ceil, 1, kFoldable | kJumps, "ceil(x)")                                      \
    X(Round, 1, kFoldable | kJumps, "round(x)")                                    \
    X(Asin, 1, kFoldable, "asin(x)")                                               \
    X(Acos, 1, kFoldable, "acos(x)")                                               \
    X(Atan, 1, kFoldable, "atan(x)")                                               \
    X(Not, 1, kFoldable | kTruth | kJumps, "!x")                                   \
    X(Add, 2, kFoldable | kCommutative | kSwapsExactly, "x + y")                   \
    X(Sub, 2, kFoldable, "x - y")                                                  \
    X(Mul, 2, kFoldable | kCommutative | kSwapsExactly, "x * y")                   \
    X(Div, 2, kFoldable, "x / y")                                                  \
    X(Pow, 2, kFoldable, "pow(x, y)")                                              \
    X(Min, 2, kFoldable | kCommutative, "min(x, y)")                               \
    X(Max, 2, kFoldable | kCommutative, "max(x, y)")                               \
    X(Atan2, 2, kFoldable | kPointwiseSlope, "atan(y, x)")                         \
    X(Lt, 2, kFoldable | kTruth | kJumps, "x < y")                                 \
    X(Le, 2, kFoldable | kTruth | kJumps, "x <= y")                                \
    X(Eq, 2, kFoldable | kTruth | kCommutative | kSwapsExactly | kJumps, "x == y") \
    X(Ne, 2, kFoldable | kTruth | kCommutative | kSwapsExactly | kJumps, "x != y") \
    X(And, 2, kFoldable | kTruth | kCommutative | kJumps, "x && y")                \
    X(Or, 2, kFoldable | kTruth | kCommutative | kJumps, "x || y")                 \
    X(Select, 3, kFoldable | kJumps, "c ? x : y")                                  \
    X(Noise, -1, kFoldable, "noise(p)")                                            \
    X(PNoise, -1, kFoldable, "pnoise(p, period)")                                  \
    X(CellNoise, -1, kFoldable | kJumps, "cellnoise(p)")                           \
    X(Texture, -1, kPointwiseSlope, "texture(name, s, t)")                         \
    X(Light, -1, 0, "the L and Cl of a light (illuminance)")                       \
    X(Trace, -1, 0, "trace(P, R)")

enum class Operation : uint8_t {
    None,  // not an operation: LoadK, Move, Ext
#define AFFRAY_OPERATION_ENUM(name, operands, flags, rsl) name,
    AFFRAY_OPERATIONS(AFFRAY_OPERATION_ENUM)
#undef AFFRAY_OPERATION_ENUM
};

#define AFFRAY_OPERATION_COUNT(name, operands, flags, rsl) +1
inline constexpr int kOperationCount = 1 AFFRAY_OPERATIONS(AFFRAY_OPERATION_COUNT);
#undef AFFRAY_OPERATION_COUNT

struct OperationInfo {
    const char* name;
    int operands;  // -1: varies with the opcode (the noise and texture functions)
    uint8_t flags;
    const char* rsl;
};

inline constexpr OperationInfo kOperationInfo[] = {{"None", 0, 0, ""},
#define AFFRAY_OPERATION_INFO(name, operands, flags, rsl) {#name, operands, flags, rsl},
                                                   AFFRAY_OPERATIONS(AFFRAY_OPERATION_INFO)
#undef AFFRAY_OPERATION_INFO
};

constexpr const OperationInfo& Info(Operation f) { return kOperationInfo[static_cast<int>(f)]; }
constexpr bool Has(Operation f, OperationFlag flag) { return (Info(f).flags & flag) != 0; }

//  X(name, number, format, operation, meaning)
#define AFFRAY_OPCODES(X)                                                                               \
    X(LoadK, 0, "wk-", None, "R[A] := K[B]")                                                            \
    X(Move, 1, "wr-", None, "R[A] := R[B]")                                                             \
    X(Neg, 2, "wr-", Neg, "R[A] := -R[B]")                                                              \
    X(AddRR, 3, "wrr", Add, "R[A] := R[B] + R[C]")                                                      \
    X(AddRK, 4, "wrk", Add, "R[A] := R[B] + K[C]")                                                      \
    X(SubRR, 5, "wrr", Sub, "R[A] := R[B] - R[C]")                                                      \
    X(SubRK, 6, "wrk", Sub, "R[A] := R[B] - K[C]")                                                      \
    X(SubKR, 7, "wkr", Sub, "R[A] := K[B] - R[C]")                                                      \
    X(MulRR, 8, "wrr", Mul, "R[A] := R[B] * R[C]")                                                      \
    X(MulRK, 9, "wrk", Mul, "R[A] := R[B] * K[C]")                                                      \
    X(DivRR, 10, "wrr", Div, "R[A] := R[B] / R[C]")                                                     \
    X(DivRK, 11, "wrk", Div, "R[A] := R[B] / K[C]")                                                     \
    X(DivKR, 12, "wkr", Div, "R[A] := K[B] / R[C]")                                                     \
    X(Sqr, 13, "wr-", Sqr, "R[A] := R[B] * R[B]  (one operand: bounds stay correlated)")                \
    X(Sqrt, 14, "wr-", Sqrt, "R[A] := sqrt(R[B])")                                                      \
    X(Exp, 15, "wr-", Exp, "R[A] := exp(R[B])")                                                         \
    X(Log, 16, "wr-", Log, "R[A] := log(R[B])  (natural)")                                              \
    X(Sin, 17, "wr-", Sin, "R[A] := sin(R[B])")                                                         \
    X(Cos, 18, "wr-", Cos, "R[A] := cos(R[B])")                                                         \
    X(Abs, 19, "wr-", Abs, "R[A] := |R[B]|")                                                            \
    X(Sign, 20, "wr-", Sign, "R[A] := sign(R[B])  (-1, 0 or 1)")                                        \
    X(PowRR, 21, "wrr", Pow, "R[A] := pow(R[B], R[C])")                                                 \
    X(PowRK, 22, "wrk", Pow, "R[A] := pow(R[B], K[C])")                                                 \
    X(DerivU, 23, "wr-", DerivU, "R[A] := d R[B] / du  (needs a number type with derivatives)")         \
    X(DerivV, 24, "wr-", DerivV, "R[A] := d R[B] / dv")                                                 \
    X(Floor, 25, "wr-", Floor, "R[A] := floor(R[B])")                                                   \
    X(Ceil, 26, "wr-", Ceil, "R[A] := ceil(R[B])")                                                      \
    X(Round, 27, "wr-", Round, "R[A] := round(R[B])  (halves away from 0)")                             \
    X(Asin, 28, "wr-", Asin, "R[A] := asin(R[B])")                                                      \
    X(Acos, 29, "wr-", Acos, "R[A] := acos(R[B])")                                                      \
    X(Atan, 30, "wr-", Atan, "R[A] := atan(R[B])")                                                      \
    X(Not, 31, "wr-", Not, "R[A] := R[B] == 0")                                                         \
    X(Atan2RR, 32, "wrr", Atan2, "R[A] := atan2(R[B], R[C])  (y, x)")                                   \
    X(MinRR, 33, "wrr", Min, "R[A] := min(R[B], R[C])")                                                 \
    X(MinRK, 34, "wrk", Min, "R[A] := min(R[B], K[C])")                                                 \
    X(MaxRR, 35, "wrr", Max, "R[A] := max(R[B], R[C])")                                                 \
    X(MaxRK, 36, "wrk", Max, "R[A] := max(R[B], K[C])")                                                 \
    X(LtRR, 37, "wrr", Lt, "R[A] := R[B] < R[C]")                                                       \
    X(LtRK, 38, "wrk", Lt, "R[A] := R[B] < K[C]")                                                       \
    X(LtKR, 39, "wkr", Lt, "R[A] := K[B] < R[C]")                                                       \
    X(LeRR, 40, "wrr", Le, "R[A] := R[B] <= R[C]")                                                      \
    X(LeRK, 41, "wrk", Le, "R[A] := R[B] <= K[C]")                                                      \
    X(LeKR, 42, "wkr", Le, "R[A] := K[B] <= R[C]")                                                      \
    X(EqRR, 43, "wrr", Eq, "R[A] := R[B] == R[C]")                                                      \
    X(EqRK, 44, "wrk", Eq, "R[A] := R[B] == K[C]")                                                      \
    X(NeRR, 45, "wrr", Ne, "R[A] := R[B] != R[C]")                                                      \
    X(NeRK, 46, "wrk", Ne, "R[A] := R[B] != K[C]")                                                      \
    X(AndRR, 47, "wrr", And, "R[A] := R[B] != 0 && R[C] != 0")                                          \
    X(OrRR, 48, "wrr", Or, "R[A] := R[B] != 0 || R[C] != 0")                                            \
    X(Select, 49, "wrrr--", Select, "R[A] := R[B] != 0 ? R[C] : R[D]  (undecided: a bound of both)")    \
    X(Ext, 50, "---", None, "further operands of the instruction before; never runs on its own")        \
    X(Noise1, 51, "wr-", Noise, "R[A] := noise(R[B]), channel = flags")                                 \
    X(Noise2, 52, "wrr", Noise, "R[A] := noise(R[B], R[C])")                                            \
    X(Noise3, 53, "wrrr--", Noise, "R[A] := noise(R[B], R[C], R[D])")                                   \
    X(Noise4, 54, "wrrrr-", Noise, "R[A] := noise(R[B], R[C], R[D], R[E])")                             \
    X(PNoise1, 55, "wrr", PNoise, "R[A] := pnoise(x; period), operands x then period")                  \
    X(PNoise2, 56, "wrrrr-", PNoise, "R[A] := pnoise(x, y; periods)")                                   \
    X(PNoise3, 57, "wrrrrrr--", PNoise, "R[A] := pnoise(x, y, z; periods)")                             \
    X(PNoise4, 58, "wrrrrrrrr", PNoise, "R[A] := pnoise(x, y, z, w; periods)")                          \
    X(CellNoise1, 59, "wr-", CellNoise, "R[A] := cellnoise(R[B]), channel = flags")                     \
    X(CellNoise2, 60, "wrr", CellNoise, "R[A] := cellnoise(R[B], R[C])")                                \
    X(CellNoise3, 61, "wrrr--", CellNoise, "R[A] := cellnoise(R[B], R[C], R[D])")                       \
    X(CellNoise4, 62, "wrrrr-", CellNoise, "R[A] := cellnoise(R[B], R[C], R[D], R[E])")                 \
    X(Tan, 63, "wr-", Tan, "R[A] := tan(R[B])")                                                         \
    X(Texture2, 64, "wrr", Texture, "R[A] := texture(slot flags; s = R[B], t = R[C])")                  \
    X(Texture8, 65, "wrrrrrrrr", Texture, "R[A] := texture(slot flags; corners s1, t1 ... s4, t4)")     \
    X(Light, 66, "wrr", Light, "R[A] := component R[C] of light slot flags; R[B] != 0: shadows wanted") \
    X(Trace, 67, "wrrr--", Trace, "R[A] := channel flags of the colour seen along (R[B], R[C], R[D])")

enum class Op : uint8_t {
#define AFFRAY_OP_ENUM(name, number, format, operation, meaning) name = number,
    AFFRAY_OPCODES(AFFRAY_OP_ENUM)
#undef AFFRAY_OP_ENUM
};

#define AFFRAY_OP_COUNT(name, number, format, operation, meaning) +1
inline constexpr int kOpCount = 0 AFFRAY_OPCODES(AFFRAY_OP_COUNT);
#undef AFFRAY_OP_COUNT

inline constexpr int kMaxRegisters = 1 << 16;
inline constexpr int kMaxConstants = 1 << 16;

struct Instr {
    Op op;
    uint8_t flags = 0;  // a noise channel or a texture slot (see the encoding above); else 0
    uint16_t a = 0, b = 0, c = 0;
};
static_assert(sizeof(Instr) == 8, "instructions are 8 bytes (see the encoding above)");

/// Static facts about one opcode, generated from the list.
struct OpInfo {
    const char* name;
    const char* format;  // letters from "wrk-": A, B and C, then A, B, C of each Ext word
    Operation operation;
    const char* meaning;
};

/// How an opcode takes its operands: all from registers, or its second (RK) or first (KR) from
/// the constants.
enum class OperandForm : uint8_t { RR, RK, KR };

/// Words (Instr) an instruction of this format takes: itself and its Ext words.
constexpr int WordCount(const char* format) {
    int n = 0;
    while (format[n]) ++n;
    return n / 3;
}

inline constexpr OpInfo kOpInfo[] = {
#define AFFRAY_OP_INFO(name, number, format, operation, meaning) {#name, format, Operation::operation, meaning},
    AFFRAY_OPCODES(AFFRAY_OP_INFO)
#undef AFFRAY_OP_INFO
};

// The numbers must be 0..kOpCount-1 in order, so kOpInfo can be indexed by the opcode.
#define AFFRAY_OP_CHECK(op, number, format, operation, meaning)            \
    static_assert(static_cast<int>(Op::op) == number && number < kOpCount, \
                  "opcodes must be numbered 0, 1, 2... in order");
AFFRAY_OPCODES(AFFRAY_OP_CHECK)
#undef AFFRAY_OP_CHECK

// ...and listed in that order, so that kOpInfo[number] describes opcode `number`.
namespace detail {
#define AFFRAY_OP_NUMBER(op, number, format, operation, meaning) number,
inline constexpr int kOpNumbersInListOrder[] = {AFFRAY_OPCODES(AFFRAY_OP_NUMBER)};
#undef AFFRAY_OP_NUMBER
constexpr bool OpsListedInOrder() {
    for (int i = 0; i < kOpCount; ++i)
        if (kOpNumbersInListOrder[i] != i) return false;
    return true;
}
static_assert(OpsListedInOrder(), "list the opcodes in the order of their numbers");
}  // namespace detail

// Every format is whole words of three letters.
#define AFFRAY_OP_FORMAT_CHECK(op, number, format, operation, meaning) \
    static_assert(sizeof(format) - 1 >= 3 && (sizeof(format) - 1) % 3 == 0, "formats are 3 letters per word");
AFFRAY_OPCODES(AFFRAY_OP_FORMAT_CHECK)
#undef AFFRAY_OP_FORMAT_CHECK

constexpr const OpInfo& Info(Op op) { return kOpInfo[static_cast<int>(op)]; }

/// The operation an opcode implements (None for LoadK, Move and Ext).
constexpr Operation OperationOf(Op op) { return Info(op).operation; }

/// The operands an opcode reads (the 'r' and 'k' letters of its format).
constexpr int OperandCount(Op op) {
    int n = 0;
    for (const char* f = Info(op).format; *f; ++f) n += *f == 'r' || *f == 'k';
    return n;
}

/// The operand form of an opcode (from the letters of B and C).
constexpr OperandForm FormOf(Op op) {
    const char* f = Info(op).format;
    return f[1] == 'k' ? OperandForm::KR : f[2] == 'k' ? OperandForm::RK : OperandForm::RR;
}

/// The opcode implementing `f` with `count` operands in `form`, or Op::Ext if the VM has none.
constexpr Op OpcodeFor(Operation f, int count, OperandForm form) {
    for (int i = 0; i < kOpCount; ++i) {
        const Op op = static_cast<Op>(i);
        if (f != Operation::None && OperationOf(op) == f && OperandCount(op) == count && FormOf(op) == form) return op;
    }
    return Op::Ext;
}

/// The opcode computing the same as the all-register opcode `op` with its operand `i` (1 = B,
/// 2 = C) taken from the constants, or Op::Ext if there is none. The result takes the register
/// and the constant in the order of its format, so for a constant B it may swap the operands:
/// only where the operation swaps exactly.
constexpr Op ConstantFormOf(Op op, int i) {
    const Operation f = OperationOf(op);
    if (FormOf(op) != OperandForm::RR || OperandCount(op) != 2) return Op::Ext;
    if (i == 2) return OpcodeFor(f, 2, OperandForm::RK);
    const Op kr = OpcodeFor(f, 2, OperandForm::KR);
    if (kr != Op::Ext || !Has(f, kSwapsExactly)) return kr;
    return OpcodeFor(f, 2, OperandForm::RK);
}

/// Whether the opcode's scalar result is exactly 1.0 or +0.0.
constexpr bool GivesTruth(Op op) { return Has(OperationOf(op), kTruth); }

// Every operation has its all-register opcode, with the operation's operand count.
namespace detail {
constexpr bool EveryOperationHasAnOpcode() {
    for (int f = 1; f < kOperationCount; ++f) {
        const Operation op = static_cast<Operation>(f);
        bool found = false;
        for (int i = 0; i < kOpCount; ++i) {
            const Op o = static_cast<Op>(i);
            if (OperationOf(o) != op) continue;
            if (Info(op).operands >= 0 && OperandCount(o) != Info(op).operands) return false;
            found = found || FormOf(o) == OperandForm::RR;
        }
        if (!found) return false;
    }
    return true;
}
static_assert(EveryOperationHasAnOpcode(), "each operation needs an all-register opcode with its operand count");
}  // namespace detail

/// Words each opcode's instructions take (WordCount of its format), as a table.
inline constexpr uint8_t kOpWords[] = {
#define AFFRAY_OP_WORDS(name, number, format, operation, meaning) static_cast<uint8_t>(WordCount(format)),
    AFFRAY_OPCODES(AFFRAY_OP_WORDS)
#undef AFFRAY_OP_WORDS
};
inline int Words(Op op) { return kOpWords[static_cast<int>(op)]; }

/// Operand `i` of the instruction starting at `in` (0 = its A, 1 = B, 2 = C, 3 = the first Ext
/// word's A, ...), following format letter i. The caller checks the Ext words exist.
inline uint16_t OperandOf(const Instr* in, int i) {
    const Instr& word = in[i / 3];
    return i % 3 == 0 ? word.a : i % 3 == 1 ? word.b : word.c;
}

}  // namespace affray::vm
