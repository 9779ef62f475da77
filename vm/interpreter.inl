// vm/interpreter.inl: the dispatch loop, written once for every number type.
// Included only by the interpreter_<type>.cpp files, which instantiate it explicitly.
// Each case is a line or two; anything longer belongs in the number types' free functions.
// Build with -DAFFRAY_TRACE_VM to print every instruction and its result as it runs.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>

#include "vm/interpreter.h"
#include "vm/numbers/noise.h"
#include "vm/texture_lookup.h"

#ifdef AFFRAY_TRACE_VM
#include <cstdio>

#include "vm/disasm.h"
#endif

namespace affray::vm {

namespace detail {

// Whether a < b at every point of the region (-1), a > b (1), or neither is proved (0), from the
// ranges. Strict, so that fmin/fmax give that operand bit for bit (where a == b they may differ in
// the sign of 0). An affine Min or Max decides from the form a - b, which also orders correlated
// operands whose ranges overlap; recording does not, because that costs an affine subtraction per
// Min or Max, and on the shaders in shaders/ it decided nothing more.
inline int StrictOrder(const Interval& a, const Interval& b) {
    if (a.isUnbounded() || b.isUnbounded()) return 0;
    return a.hi() < b.lo() ? -1 : b.hi() < a.lo() ? 1 : 0;
}

// The one double every value of x stands for, if x is a bound that proves it; a point value
// proves nothing about a region. A dual's value may be constant where its derivatives are not
// zero (a bound's point value is not the function's), so a dual is a constant only with both
// derivatives exactly zero as well: then LoadK, whose derivatives are zero, stands for it.
inline bool PointValue(double, double*) { return false; }
inline bool PointValue(const Interval& x, double* c) {
    if (x.isUnbounded() || !x.isPoint()) return false;
    *c = x.lo();
    return true;
}
inline bool PointValue(const Affine& x, double* c) {
    if (!x.isConstant()) return false;  // no terms, no error: the form is its center exactly
    *c = x.center();
    return true;
}
inline bool PointValue(const ReducedAffine& x, double* c) {
    if (!x.isConstant()) return false;  // no terms, no error: the form is its center exactly
    *c = x.center();
    return true;
}
template <class T>
bool PointValue(const Dual<T>& x, double* c) {
    return IsExactlyZero(x.du) && IsExactlyZero(x.dv) && PointValue(x.v, c);
}

// The constant result `x` of `op` stands for at every point, or Decisions::kNone. The scalar
// result lies in the bound [c, c], so it is c, except that -0.0 == 0.0: a zero is taken only
// from an opcode whose zero is +0.0.
template <class T>
double ResultConstant(Op op, const T& x) {
    double c;
    if (op == Op::LoadK || !PointValue(x, &c)) return Decisions::kNone;
    if (c != 0) return c;
    return GivesTruth(op) ? 0.0 : Decisions::kNone;  // (vm/opcodes.h: kTruth)
}

}  // namespace detail

template <class T>
T Interpreter<T>::LightValue(uint8_t slot, const T& shadowed, const T& component) const {
    if constexpr (std::is_same_v<T, double> || std::is_same_v<T, Dual<double>>) {
        auto value = [](const T& x) {
            if constexpr (std::is_same_v<T, double>)
                return x;
            else
                return x.v;
        };
        if (!m_lights) return T(0.0);
        return T(m_lights->Light(slot, static_cast<int>(value(component)), value(shadowed) != 0));
    } else {
        return T(std::numeric_limits<double>::quiet_NaN());  // every number type's "unbounded"
    }
}

template <class T>
T Interpreter<T>::TraceValue(uint8_t channel, const T* direction) const {
    if constexpr (std::is_same_v<T, double> || std::is_same_v<T, Dual<double>>) {
        if (!m_lights) return T(0.0);
        const double d[3] = {ValueOf(direction[0]), ValueOf(direction[1]), ValueOf(direction[2])};
        return T(m_lights->Trace(d, channel));
    } else {
        return T(std::numeric_limits<double>::quiet_NaN());  // every number type's "unbounded"
    }
}

template <class T>
Interpreter<T>::Interpreter(const Program& program) : m_program(&program) {
    for (const ProgramParam& p : program.params) m_paramValues.push_back(p.defaults);
    SetProgram(program);
}

template <class T>
void Interpreter<T>::SetProgram(const Program& program) {
    if (program.params.size() != m_paramValues.size()) {
        m_paramValues.clear();
        for (const ProgramParam& p : program.params) m_paramValues.push_back(p.defaults);
    }
    m_program = &program;
    m_registers.resize(program.registerCount, T(0.0));
    // A point type (double, Dual<double>) never straddles an integer: no need to save inputs.
    const bool pointType = std::is_same_v<T, double> || std::is_same_v<T, Dual<double>>;
    m_splits = false;
    for (const Instr& in : program.code)
        if (in.op == Op::Floor || in.op == Op::Ceil || in.op == Op::Round) m_splits = !pointType;
}

template <class T>
uint8_t Interpreter<T>::Choice(const Instr* in, const T* R, double* constant) const {
    const double* K = m_program->constants.data();
    // The operand numbers are format letters: 1 = B, 2 = C, 3 = the Ext word's A (Select's D).
    switch (in->op) {
        case Op::Select: {
            const Truth t = TruthOf(R[in->b]);
            return t == Truth::True ? 2 : t == Truth::False ? 3 : 0;
        }
        case Op::MinRR:
        case Op::MaxRR: {
            const int order = detail::StrictOrder(RangeOf(ValueOf(R[in->b])), RangeOf(ValueOf(R[in->c])));
            if (order == 0) return 0;
            return (order < 0) == (in->op == Op::MinRR) ? 1 : 2;
        }
        case Op::MinRK:
        case Op::MaxRK: {
            const int order = detail::StrictOrder(RangeOf(ValueOf(R[in->b])), Interval(K[in->c]));
            if (order == 0) return 0;
            if ((order < 0) == (in->op == Op::MinRK)) return 1;
            *constant = K[in->c];
            return 0;
        }
        default: return 0;
    }
}

template <class T>
template <class F, class B>
T Interpreter<T>::Rounding(const T& x, F f, B bounded) {
    if (m_splits && m_decisionIndex < static_cast<size_t>(kMaxSplits)) {
        const Interval r = RangeOf(ValueOf(x));
        const double lo = f(r.lo()), hi = f(r.hi());
        if (!r.isUnbounded() && hi == lo + 1) {
            const size_t i = m_decisionIndex++;
            if (i == m_decisions.size()) m_decisions.push_back(0);
            return T(m_decisions[i] ? hi : lo);
        }
    }
    return bounded(x);
}

template <class T>
void Interpreter<T>::Run() {
    if (m_recording) m_record.Begin(m_program->code.size());
    if (!m_splits) {
        RunPass();
        return;
    }
    // Depth-first over the decisions: run, join the outputs, flip the last lower decision to
    // upper (dropping those after it), restore the inputs, run again; until all are upper.
    m_saved = m_registers;
    m_decisions.clear();
    m_joined.clear();
    for (bool first = true;; first = false) {
        m_decisionIndex = 0;
        // A choice decided differently by two cases is not decided over the region.
        if (m_recording && !first) m_record.NextRun();
        RunPass();
        size_t j = 0;
        for (const ProgramOutput& out : m_program->outputs)
            for (int c = 0; c < out.size; ++c, ++j) {
                const T& value = m_registers[out.registers[c]];
                if (j == m_joined.size())
                    m_joined.push_back(value);
                else
                    m_joined[j] = Join(m_joined[j], value);
            }
        while (!m_decisions.empty() && m_decisions.back() == 1) m_decisions.pop_back();
        if (m_decisions.empty()) break;
        m_decisions.back() = 1;
        m_registers = m_saved;
    }
    size_t j = 0;
    for (const ProgramOutput& out : m_program->outputs)
        for (int c = 0; c < out.size; ++c, ++j) m_registers[out.registers[c]] = m_joined[j];
}

template <class T>
void Interpreter<T>::SetParam(size_t index, const std::vector<double>& values) {
    m_paramValues[index] = values;
}

template <class T>
void Interpreter<T>::SetGlobal(Global g, const T& value) {
    uint16_t r = m_program->globalRegisters[static_cast<int>(g)];
    if (r != kNoRegister) m_registers[r] = value;
}

template <class T>
void Interpreter<T>::SetGlobal(Global g, const Vec3<T>& value) {
    uint16_t r = m_program->globalRegisters[static_cast<int>(g)];
    if (r == kNoRegister) return;
    m_registers[r] = value.x;
    m_registers[r + 1] = value.y;
    m_registers[r + 2] = value.z;
}

template <class T>
Vec3<T> Interpreter<T>::OutputTriple(const ProgramOutput& out) const {
    return {m_registers[out.registers[0]], m_registers[out.registers[1]], m_registers[out.registers[2]]};
}

template <class T>
template <bool kRecord>
void Interpreter<T>::RunOnce() {
    // For T = double the std functions are the scalar semantics, except Sqrt, Pow and Div
    // (vm/numbers/number.h); other types find theirs by ADL.
    using std::abs, std::cos, std::exp, std::log, std::sin;
    using std::acos, std::asin, std::atan, std::atan2, std::ceil, std::floor, std::round, std::tan;
    T* R = m_registers.data();
    const double* K = m_program->constants.data();
    // Parameter registers may be reused once read, so they are written before every run.
    for (size_t i = 0; i < m_program->params.size(); ++i) {
        const ProgramParam& p = m_program->params[i];
        if (p.firstRegister == kNoRegister) continue;
        for (int c = 0; c < p.size; ++c) R[p.firstRegister + c] = T(m_paramValues[i][c]);
    }
    const Instr* code = m_program->code.data();
    const size_t size = m_program->code.size();
    for (size_t pc = 0; pc < size; ++pc) {
        const Instr& in = code[pc];
        T& A = R[in.a];
        // The operands of a noise or texture function: R[B], R[C], then the Ext words' registers.
        auto noiseArgs = [&](int count, T* args) {
            for (int i = 0; i < count; ++i) args[i] = R[OperandOf(&in, i + 1)];
        };
        [[maybe_unused]] uint8_t operand = 0;
        [[maybe_unused]] double constant = Decisions::kNone;
        if constexpr (kRecord)
            if (in.op == Op::Select || (in.op >= Op::MinRR && in.op <= Op::MaxRK)) operand = Choice(&in, R, &constant);
        switch (in.op) {
            case Op::LoadK: A = T(K[in.b]); break;
            case Op::Move: A = R[in.b]; break;
            case Op::Neg: A = -R[in.b]; break;
            case Op::AddRR: A = R[in.b] + R[in.c]; break;
            case Op::AddRK: A = R[in.b] + K[in.c]; break;
            case Op::SubRR: A = R[in.b] - R[in.c]; break;
            case Op::SubRK: A = R[in.b] - K[in.c]; break;
            case Op::SubKR: A = K[in.b] - R[in.c]; break;
            case Op::MulRR: A = R[in.b] * R[in.c]; break;
            case Op::MulRK: A = R[in.b] * K[in.c]; break;
            case Op::DivRR: A = Div(R[in.b], R[in.c]); break;
            case Op::DivRK: A = Div(R[in.b], K[in.c]); break;
            case Op::DivKR: A = Div(K[in.b], R[in.c]); break;
            case Op::Sqr: A = sqr(R[in.b]); break;
            case Op::Sqrt: A = Sqrt(R[in.b]); break;
            case Op::Exp: A = exp(R[in.b]); break;
            case Op::Log: A = log(R[in.b]); break;
            case Op::Sin: A = sin(R[in.b]); break;
            case Op::Cos: A = cos(R[in.b]); break;
            case Op::Abs: A = abs(R[in.b]); break;
            case Op::Sign: A = sign(R[in.b]); break;
            case Op::PowRR: A = Pow(R[in.b], R[in.c]); break;
            case Op::PowRK: A = Pow(R[in.b], T(K[in.c])); break;
            case Op::DerivU: A = DerivU(R[in.b]); break;
            case Op::DerivV: A = DerivV(R[in.b]); break;
            case Op::Floor:
                A = Rounding(
                    R[in.b], [](double x) { return std::floor(x); }, [](const T& x) { return floor(x); });
                break;
            case Op::Ceil:
                A = Rounding(
                    R[in.b], [](double x) { return std::ceil(x); }, [](const T& x) { return ceil(x); });
                break;
            case Op::Round:
                A = Rounding(
                    R[in.b], [](double x) { return std::round(x); }, [](const T& x) { return round(x); });
                break;
            case Op::Asin: A = asin(R[in.b]); break;
            case Op::Acos: A = acos(R[in.b]); break;
            case Op::Atan: A = atan(R[in.b]); break;
            case Op::Not: A = Not(R[in.b]); break;
            case Op::Atan2RR: A = atan2(R[in.b], R[in.c]); break;
            case Op::MinRR: A = Min(R[in.b], R[in.c]); break;
            case Op::MinRK: A = Min(R[in.b], T(K[in.c])); break;
            case Op::MaxRR: A = Max(R[in.b], R[in.c]); break;
            case Op::MaxRK: A = Max(R[in.b], T(K[in.c])); break;
            case Op::LtRR: A = Less(R[in.b], R[in.c]); break;
            case Op::LtRK: A = Less(R[in.b], T(K[in.c])); break;
            case Op::LtKR: A = Less(T(K[in.b]), R[in.c]); break;
            case Op::LeRR: A = LessEq(R[in.b], R[in.c]); break;
            case Op::LeRK: A = LessEq(R[in.b], T(K[in.c])); break;
            case Op::LeKR: A = LessEq(T(K[in.b]), R[in.c]); break;
            case Op::EqRR: A = Equal(R[in.b], R[in.c]); break;
            case Op::EqRK: A = Equal(R[in.b], T(K[in.c])); break;
            case Op::NeRR: A = NotEqual(R[in.b], R[in.c]); break;
            case Op::NeRK: A = NotEqual(R[in.b], T(K[in.c])); break;
            case Op::AndRR: A = And(R[in.b], R[in.c]); break;
            case Op::OrRR: A = Or(R[in.b], R[in.c]); break;
            case Op::Select: A = Select(R[in.b], R[in.c], R[code[pc + 1].a]); break;
            case Op::Ext: break;  // the verifier rules out an Ext word on its own
            case Op::Noise1:
            case Op::Noise2:
            case Op::Noise3:
            case Op::Noise4: {
                const int dims = static_cast<int>(in.op) - static_cast<int>(Op::Noise1) + 1;
                T args[4];
                noiseArgs(dims, args);
                A = Noise(args, dims, in.flags);
                break;
            }
            case Op::PNoise1:
            case Op::PNoise2:
            case Op::PNoise3:
            case Op::PNoise4: {
                const int dims = static_cast<int>(in.op) - static_cast<int>(Op::PNoise1) + 1;
                T args[8];
                noiseArgs(2 * dims, args);
                A = PNoise(args, args + dims, dims, in.flags);
                break;
            }
            case Op::CellNoise1:
            case Op::CellNoise2:
            case Op::CellNoise3:
            case Op::CellNoise4: {
                const int dims = static_cast<int>(in.op) - static_cast<int>(Op::CellNoise1) + 1;
                T args[4];
                noiseArgs(dims, args);
                A = CellNoise(args, dims, in.flags);
                break;
            }
            case Op::Tan: A = tan(R[in.b]); break;
            case Op::Texture2: A = TextureLookup((*m_program->textures)[in.flags], R[in.b], R[in.c]); break;
            case Op::Texture8: {
                T args[8];
                noiseArgs(8, args);
                A = TextureLookupQuad((*m_program->textures)[in.flags], args);
                break;
            }
            case Op::Light: A = LightValue(in.flags, R[in.b], R[in.c]); break;
            case Op::Trace: {
                T args[3];
                noiseArgs(3, args);
                A = TraceValue(in.flags, args);
                break;
            }
        }
        if constexpr (kRecord) {
            if (std::isnan(constant)) constant = detail::ResultConstant(in.op, A);
            m_record.Observe(pc, operand, constant);
        }
#ifdef AFFRAY_TRACE_VM
        std::fprintf(stderr, "[%s] %-40s -> %s\n", NumberTraits<T>::kName,
                     DisassembleInstr(*m_program, &in, size - pc).c_str(), ToString(A).c_str());
#endif
        pc += Words(in.op) - 1;  // skip the Ext words
    }
}

}  // namespace affray::vm
