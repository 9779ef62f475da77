// vm/interpreter.h: the one interpreter, templated on the number type.
// The same program runs as plain doubles (a point), Interval, Affine or ReducedAffine (a bound
// over a region of the surface) and Dual (exact derivatives for normals): only the number type
// differs, never the loop. Explicit instantiations live in interpreter_<type>.cpp, all from interpreter.inl.
#pragma once

#include <vector>

#include "vm/lights.h"
#include "vm/numbers/number.h"
#include "vm/numbers/vec3.h"
#include "vm/program.h"
#include "vm/prune.h"

namespace affray::vm {

template <class T>
class Interpreter {
  public:
    /// `program` must have passed Verify() and must outlive the interpreter.
    explicit Interpreter(const Program& program);

    const Program& program() const { return *m_program; }

    /// Runs `program` from now on, which must have passed Verify() and outlive its use. It must
    /// take the same parameters as the previous program (as a pruned program does): their values
    /// carry over. Allocates only if the program needs more registers than any before.
    void SetProgram(const Program& program);

    /// While on, every Run() records in decisions() what it proved about each instruction over
    /// the region of its inputs (see vm/prune.h), for Prune. Off by default; off, the loop runs
    /// without any recording code (it is instantiated twice).
    void SetRecording(bool on) { m_recording = on; }
    /// The record of the last Run() made with recording on.
    const Decisions& decisions() const { return m_record; }

    /// Sets a global the program reads; a global it does not read is ignored (cheaply), so
    /// callers may set everything or ask program().readsGlobal() first to skip computing it.
    /// A global lives in a register that the program may reuse once it has read it (and a
    /// shader may assign P or N): set every global the program reads before each Run().
    void SetGlobal(Global g, const T& value);
    void SetGlobal(Global g, const Vec3<T>& value);

    /// Where Light instructions (a surface program's light loops) get their answers, or null: then
    /// every light is dark (0). Only the point types (double, Dual<double>) ask; a bound type
    /// gives the unbounded value (a verified bound or shade program has no Light instruction).
    void SetLights(LightQueries* lights) { m_lights = lights; }

    /// Sets parameter `index` of program().params (size values) for the following runs; until
    /// then a parameter has its default. Specialised programs have no parameters.
    void SetParam(size_t index, const std::vector<double>& values);

    /// Runs the program over the current globals and parameters. For a bound type, a floor, ceil
    /// or round whose argument straddles one integer is split into its two cases: the program
    /// runs once per combination (at most 2^kMaxSplits runs) with that result a constant, and the
    /// outputs are the Join of the runs. Every case is a valid bound of the points it covers, so
    /// the Join contains every point's result; and within a case the pattern a floor cuts (a
    /// tile, a brick, a cell) keeps its shape, where the unsplit bound of x - floor(x) is [0, 1].
    void Run();
    static constexpr int kMaxSplits = 4;

    /// The value of an output after Run(); the output must exist.
    Vec3<T> OutputTriple(const ProgramOutput& out) const;
    const T& Register(int r) const { return m_registers[r]; }

  private:
    /// One pass over the code, with the split decisions in m_decisions; with kRecord, observing
    /// every instruction into m_record.
    template <bool kRecord>
    void RunOnce();
    void RunPass() { m_recording ? RunOnce<true>() : RunOnce<false>(); }
    /// Whether the choice instruction `in` (Select, Min, Max), about to run on the registers R, is
    /// decided over the region: the operand it gives (as Decisions::Observe takes it) or 0, or
    /// the constant in *constant (a Min or Max decided for its constant operand).
    uint8_t Choice(const Instr* in, const T* R, double* constant) const;
    /// floor/ceil/round (`f` its scalar, `bounded` its T version) of x, split as Run() says.
    template <class F, class B>
    T Rounding(const T& x, F f, B bounded);
    /// A Light instruction's value (SetLights), and a Trace instruction's.
    T LightValue(uint8_t slot, const T& shadowed, const T& component) const;
    T TraceValue(uint8_t channel, const T* direction) const;

    const Program* m_program;
    std::vector<T> m_registers;
    std::vector<std::vector<double>> m_paramValues;
    // Splitting (see Run): whether this program and type can split at all, the decision (0: the
    // lower integer, 1: the upper) for each split met so far in this pass, the registers as they
    // were before the first pass, and the outputs joined over the passes.
    bool m_splits = false;
    std::vector<uint8_t> m_decisions;
    size_t m_decisionIndex = 0;
    std::vector<T> m_saved, m_joined;
    bool m_recording = false;
    Decisions m_record;
    LightQueries* m_lights = nullptr;
};

/// The scalar VM's result of the all-register opcode `op` (OperandForm::RR) on `operands`
/// (OperandCount(op) doubles), with `flags` its flags (a noise channel): the opcode run by
/// Interpreter<double> in a program of its own. The constant folder computes with it
/// (compiler/fold.cpp), so a folded constant is what the VM computes at run time, bit for bit.
double RunScalarOpcode(Op op, const double* operands, uint8_t flags = 0);

extern template class Interpreter<double>;
extern template class Interpreter<Interval>;
extern template class Interpreter<Affine>;
extern template class Interpreter<ReducedAffine>;
extern template class Interpreter<Dual<double>>;
extern template class Interpreter<Dual<Affine>>;
extern template class Interpreter<Dual<ReducedAffine>>;
extern template class Interpreter<Dual<Interval>>;

}  // namespace affray::vm
