// vm/opcodes.h: THE list of opcodes. Nothing else in affray enumerates them: the enum, the names,
// the operand formats used by the verifier and the disassembler are all generated from this one
// X-macro. To add an opcode: append a line at the end with the next number (never renumber:
// compiled programs store these numbers), then handle it in Interpreter<T>::Run.
//
// Encoding: every instruction is 8 bytes,
//
//   bits  0..7   op      (MAXARG_OP = 255)
//   bits  8..15  unused  (reserved for flags)
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
    X(DerivV, 24, "wr-", "R[A] := d R[B] / dv")

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
    const char* format;  // three letters from "wrk-", for A, B and C
    const char* meaning;
};

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

inline const OpInfo& Info(Op op) { return kOpInfo[static_cast<int>(op)]; }

}  // namespace affray::vm
