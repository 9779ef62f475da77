// vm/opcodes.h: THE list of opcodes. Nothing else in affray enumerates them: the enum, the names,
// the operand formats used by the verifier and the disassembler are all generated from this one
// X-macro. To add an opcode: append a line at the end with the next number (never renumber:
// compiled programs store these numbers), then handle it in Interpreter<T>::Run.
//
// Encoding: every instruction is 8 bytes,
//
//   bits  0..7   op      (MAXARG_OP = 255)
//   bits  8..15  flags   (the noise functions' seed, which picks an independent channel; else 0)
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

//  X(name, number, format, meaning)
#define AFFRAY_OPCODES(X)                                                        \
    X(LoadK, 0, "wk-", "R[A] := K[B]")                                           \
    X(Move, 1, "wr-", "R[A] := R[B]")                                            \
    X(Neg, 2, "wr-", "R[A] := -R[B]")                                            \
    X(AddRR, 3, "wrr", "R[A] := R[B] + R[C]")                                    \
    X(AddRK, 4, "wrk", "R[A] := R[B] + K[C]")                                    \
    X(SubRR, 5, "wrr", "R[A] := R[B] - R[C]")                                    \
    X(SubRK, 6, "wrk", "R[A] := R[B] - K[C]")                                    \
    X(SubKR, 7, "wkr", "R[A] := K[B] - R[C]")                                    \
    X(MulRR, 8, "wrr", "R[A] := R[B] * R[C]")                                    \
    X(MulRK, 9, "wrk", "R[A] := R[B] * K[C]")                                    \
    X(DivRR, 10, "wrr", "R[A] := R[B] / R[C]")                                   \
    X(DivRK, 11, "wrk", "R[A] := R[B] / K[C]")                                   \
    X(DivKR, 12, "wkr", "R[A] := K[B] / R[C]")                                   \
    X(Sqr, 13, "wr-", "R[A] := R[B] * R[B]  (one operand: bounds stay correlated)") \
    X(Sqrt, 14, "wr-", "R[A] := sqrt(R[B])")                                     \
    X(Exp, 15, "wr-", "R[A] := exp(R[B])")                                       \
    X(Log, 16, "wr-", "R[A] := log(R[B])  (natural)")                            \
    X(Sin, 17, "wr-", "R[A] := sin(R[B])")                                       \
    X(Cos, 18, "wr-", "R[A] := cos(R[B])")                                       \
    X(Abs, 19, "wr-", "R[A] := |R[B]|")                                          \
    X(Sign, 20, "wr-", "R[A] := sign(R[B])  (-1, 0 or 1)")                       \
    X(PowRR, 21, "wrr", "R[A] := pow(R[B], R[C])")                               \
    X(PowRK, 22, "wrk", "R[A] := pow(R[B], K[C])")                               \
    X(DerivU, 23, "wr-", "R[A] := d R[B] / du  (needs a number type with derivatives)") \
    X(DerivV, 24, "wr-", "R[A] := d R[B] / dv")                                  \
    X(Floor, 25, "wr-", "R[A] := floor(R[B])")                                   \
    X(Ceil, 26, "wr-", "R[A] := ceil(R[B])")                                     \
    X(Round, 27, "wr-", "R[A] := round(R[B])  (halves away from 0)")             \
    X(Asin, 28, "wr-", "R[A] := asin(R[B])")                                     \
    X(Acos, 29, "wr-", "R[A] := acos(R[B])")                                     \
    X(Atan, 30, "wr-", "R[A] := atan(R[B])")                                     \
    X(Not, 31, "wr-", "R[A] := R[B] == 0")                                       \
    X(Atan2RR, 32, "wrr", "R[A] := atan2(R[B], R[C])  (y, x)")                   \
    X(MinRR, 33, "wrr", "R[A] := min(R[B], R[C])")                               \
    X(MinRK, 34, "wrk", "R[A] := min(R[B], K[C])")                               \
    X(MaxRR, 35, "wrr", "R[A] := max(R[B], R[C])")                               \
    X(MaxRK, 36, "wrk", "R[A] := max(R[B], K[C])")                               \
    X(LtRR, 37, "wrr", "R[A] := R[B] < R[C]")                                    \
    X(LtRK, 38, "wrk", "R[A] := R[B] < K[C]")                                    \
    X(LtKR, 39, "wkr", "R[A] := K[B] < R[C]")                                    \
    X(LeRR, 40, "wrr", "R[A] := R[B] <= R[C]")                                   \
    X(LeRK, 41, "wrk", "R[A] := R[B] <= K[C]")                                   \
    X(LeKR, 42, "wkr", "R[A] := K[B] <= R[C]")                                   \
    X(EqRR, 43, "wrr", "R[A] := R[B] == R[C]")                                   \
    X(EqRK, 44, "wrk", "R[A] := R[B] == K[C]")                                   \
    X(NeRR, 45, "wrr", "R[A] := R[B] != R[C]")                                   \
    X(NeRK, 46, "wrk", "R[A] := R[B] != K[C]")                                   \
    X(AndRR, 47, "wrr", "R[A] := R[B] != 0 && R[C] != 0")                        \
    X(OrRR, 48, "wrr", "R[A] := R[B] != 0 || R[C] != 0")                         \
    X(Select, 49, "wrrr--", "R[A] := R[B] != 0 ? R[C] : R[D]  (undecided: a bound of both)") \
    X(Ext, 50, "---", "further operands of the instruction before; never runs on its own") \
    X(Noise1, 51, "wr-", "R[A] := noise(R[B]), channel = flags")                 \
    X(Noise2, 52, "wrr", "R[A] := noise(R[B], R[C])")                            \
    X(Noise3, 53, "wrrr--", "R[A] := noise(R[B], R[C], R[D])")                   \
    X(Noise4, 54, "wrrrr-", "R[A] := noise(R[B], R[C], R[D], R[E])")             \
    X(PNoise1, 55, "wrr", "R[A] := pnoise(x; period), operands x then period")   \
    X(PNoise2, 56, "wrrrr-", "R[A] := pnoise(x, y; periods)")                    \
    X(PNoise3, 57, "wrrrrrr--", "R[A] := pnoise(x, y, z; periods)")              \
    X(PNoise4, 58, "wrrrrrrrr", "R[A] := pnoise(x, y, z, w; periods)")           \
    X(CellNoise1, 59, "wr-", "R[A] := cellnoise(R[B]), channel = flags")         \
    X(CellNoise2, 60, "wrr", "R[A] := cellnoise(R[B], R[C])")                    \
    X(CellNoise3, 61, "wrrr--", "R[A] := cellnoise(R[B], R[C], R[D])")           \
    X(CellNoise4, 62, "wrrrr-", "R[A] := cellnoise(R[B], R[C], R[D], R[E])")

enum class Op : uint8_t {
#define AFFRAY_OP_ENUM(name, number, format, meaning) name = number,
    AFFRAY_OPCODES(AFFRAY_OP_ENUM)
#undef AFFRAY_OP_ENUM
};

#define AFFRAY_OP_COUNT(name, number, format, meaning) +1
inline constexpr int kOpCount = 0 AFFRAY_OPCODES(AFFRAY_OP_COUNT);
#undef AFFRAY_OP_COUNT

inline constexpr int kMaxRegisters = 1 << 16;
inline constexpr int kMaxConstants = 1 << 16;

struct Instr {
    Op op;
    uint8_t flags = 0;  // reserved; always 0 for now
    uint16_t a = 0, b = 0, c = 0;
};
static_assert(sizeof(Instr) == 8, "instructions are 8 bytes (see the encoding above)");

/// Static facts about one opcode, generated from the list.
struct OpInfo {
    const char* name;
    const char* format;  // letters from "wrk-": A, B and C, then A, B, C of each Ext word
    const char* meaning;
};

/// Words (Instr) an instruction of this format takes: itself and its Ext words.
constexpr int WordCount(const char* format) {
    int n = 0;
    while (format[n]) ++n;
    return n / 3;
}

inline constexpr OpInfo kOpInfo[] = {
#define AFFRAY_OP_INFO(name, number, format, meaning) {#name, format, meaning},
    AFFRAY_OPCODES(AFFRAY_OP_INFO)
#undef AFFRAY_OP_INFO
};

// The numbers must be 0..kOpCount-1 in order, so kOpInfo can be indexed by the opcode.
#define AFFRAY_OP_CHECK(op, number, format, meaning) \
    static_assert(static_cast<int>(Op::op) == number && number < kOpCount, "opcodes must be numbered 0, 1, 2... in order");
AFFRAY_OPCODES(AFFRAY_OP_CHECK)
#undef AFFRAY_OP_CHECK

// ...and listed in that order, so that kOpInfo[number] describes opcode `number`.
namespace detail {
#define AFFRAY_OP_NUMBER(op, number, format, meaning) number,
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
#define AFFRAY_OP_FORMAT_CHECK(op, number, format, meaning) \
    static_assert(sizeof(format) - 1 >= 3 && (sizeof(format) - 1) % 3 == 0, "formats are 3 letters per word");
AFFRAY_OPCODES(AFFRAY_OP_FORMAT_CHECK)
#undef AFFRAY_OP_FORMAT_CHECK

inline const OpInfo& Info(Op op) { return kOpInfo[static_cast<int>(op)]; }

/// Words each opcode's instructions take (WordCount of its format), as a table.
inline constexpr uint8_t kOpWords[] = {
#define AFFRAY_OP_WORDS(name, number, format, meaning) static_cast<uint8_t>(WordCount(format)),
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
