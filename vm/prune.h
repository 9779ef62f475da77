// vm/prune.h: tape pruning, after libfive's intervalAndPush and Fidget's simplify (Keeter,
// "Massively Parallel Rendering of Complex Closed-Form Implicit Surfaces", SIGGRAPH 2020).
// Owns Decisions, what one bound evaluation of a program (all its floor-split runs) proved about
// its instructions over a region, and Prune, which turns a program and such a record into a
// shorter program equal to it at every point of that region.
// A fact may only be recorded if it holds for the *scalar* semantics at every point of the region:
// Prune replaces instructions by what the facts say, so a fact that holds only for the bounds would
// change results. To add a kind of fact: record it in Interpreter<T>::Choice or ResultConstant
// (vm/interpreter.inl), argue there why every scalar result obeys it, use it in Pruner::Prune and
// test it in tests/vm/prune_test.cpp.
#pragma once

#include <bit>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "vm/assemble.h"
#include "vm/program.h"

namespace affray::vm {

/// Per code word of the program that ran: whether the instruction's result is, at every point of
/// the region, one of its operands (a decided Select, or a Min/Max whose operands' ranges are
/// strictly ordered), and whether it is one exact double (a decided comparison, a floor over one
/// integer cell, a cell noise within one cell...).
class Decisions {
  public:
    /// Starts recording an evaluation of a program of `words` code words.
    void Begin(size_t words) {
        m_operand.assign(words, 0);
        m_constant.assign(words, kNone);
        m_merge = false;
    }
    /// Starts the next floor-split run of the same evaluation: from now on a fact survives only
    /// if this run observes it too.
    void NextRun() { m_merge = true; }
    /// What the instruction at `pc` gave in the current run: its operand `operand` (1 = B, 2 = C,
    /// 3 = the first Ext word's A) or 0, and the exact result `constant` or kNone.
    void Observe(size_t pc, uint8_t operand, double constant) {
        if (!m_merge) {
            m_operand[pc] = operand;
            m_constant[pc] = constant;
            return;
        }
        if (m_operand[pc] != operand) m_operand[pc] = 0;
        if (!SameBits(m_constant[pc], constant)) m_constant[pc] = kNone;
    }

    size_t size() const { return m_operand.size(); }
    /// The operand the instruction at `pc` gives at every point of the region, or 0.
    int operandAt(size_t pc) const { return m_operand[pc]; }
    /// True, with *value, if the instruction at `pc` gives this double at every point.
    bool constantAt(size_t pc, double* value) const {
        if (SameBits(m_constant[pc], kNone)) return false;
        *value = m_constant[pc];
        return true;
    }
    /// Facts Prune can use on `program` (the one that ran): choices, and constants of
    /// instructions other than LoadK. Zero means pruning would give the program back.
    size_t usefulCount(const Program& program) const;
    /// "pc: operand C" and "pc: = 3" lines, one per fact.
    std::string ToString() const;

    /// No constant: a NaN, which a bounded value never is.
    static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

  private:
    static bool SameBits(double a, double b) { return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b); }

    std::vector<uint8_t> m_operand;
    std::vector<double> m_constant;
    bool m_merge = false;
};

/// Whether `program`'s derivative bounds over a region can bound how far its values move across
/// it (the mean value theorem, which a Newton certificate rests on: renderer/newton.h): none of
/// its instructions reads derivatives (Du, Dv: the derivatives of their results are not tracked)
/// or has pointwise slope bounds only (kPointwiseSlope: atan2, texture).
bool SlopesCanBound(const Program& program);
/// Whether `program` has an instruction that jumps (kJumps): only then need JumpsDecided be asked,
/// and the evaluation recorded.
bool HasJumps(const Program& program);
/// Whether every instruction of `program` that jumps (kJumps) is decided over the region
/// `decisions` were recorded over (a Select's operand, a constant for the others, in every
/// floor-split run). With SlopesCanBound, the program is then, over the region, a composition of
/// continuous functions, each Lipschitz where its derivative bound is finite (abs, min and max
/// join the derivatives of both sides where undecided, which holds their generalised gradients),
/// so finite derivative bounds bound the change of every value: f(x) - f(y) lies in J (x - y).
bool JumpsDecided(const Program& program, const Decisions& decisions);

/// Builds, into *out, the program equal to `program` at every point of the region `decisions`
/// were recorded over, bit for bit in the scalar semantics: an instruction with a constant result
/// becomes LoadK, one that gives an operand disappears (its readers read that operand), moves
/// disappear the same way, a register operand known to be a constant becomes a constant operand
/// where the opcode has such a form (AddRR -> AddRK), and whatever no output depends on any more
/// is removed: the value numbering is the pruner's own, the rest (liveness, registers, the
/// constant pool; vm/assemble.h) the back end it shares with the compiler's emitter. Globals and
/// parameters no longer read get kNoRegister; the constant pool keeps only what the code reads. Its bounds over any sub-region
/// contain its scalar results, as any program's do. `decisions` must come from running `program`
/// (same code size). *out may be reused: its vectors keep their capacity.
class Pruner {
  public:
    void Prune(const Program& program, const Decisions& decisions, Program* out);

  private:
    Assembler m_assembler;                // the back end it shares with the compiler's emitter
    std::vector<int> m_regValue;          // the value each original register holds
    std::vector<double> m_valueConstant;  // per value: the constant it is loaded with, or kNone
};

/// Pruner().Prune, for callers that prune once.
Program Prune(const Program& program, const Decisions& decisions);

}  // namespace affray::vm
