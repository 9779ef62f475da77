// vm/interpreter.inl: the dispatch loop, written once for every number type.
// Included only by the interpreter_<type>.cpp files, which instantiate it explicitly.
// Each case is a line or two; anything longer belongs in the number types' free functions.
// Build with -DAFFRAY_TRACE_VM to print every instruction and its result as it runs.
#pragma once

#include <cmath>

#include "vm/interpreter.h"

#ifdef AFFRAY_TRACE_VM
#include <cstdio>

#include "vm/disasm.h"
#endif

namespace affray::vm {

template <class T>
Interpreter<T>::Interpreter(const Program& program)
    : m_program(&program), m_registers(program.registerCount, T(0.0)) {
    for (const ProgramParam& p : program.params) m_paramValues.push_back(p.defaults);
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
    return {m_registers[out.registers[0]], m_registers[out.registers[1]],
            m_registers[out.registers[2]]};
}

template <class T>
void Interpreter<T>::Run() {
    // For T = double the std functions are the scalar semantics; other types find theirs by ADL.
    using std::abs, std::cos, std::exp, std::log, std::pow, std::sin, std::sqrt;
    T* R = m_registers.data();
    const double* K = m_program->constants.data();
    // Parameter registers may be reused once read, so they are written before every run.
    for (size_t i = 0; i < m_program->params.size(); ++i) {
        const ProgramParam& p = m_program->params[i];
        if (p.firstRegister == kNoRegister) continue;
        for (int c = 0; c < p.size; ++c) R[p.firstRegister + c] = T(m_paramValues[i][c]);
    }
    for (const Instr& in : m_program->code) {
        T& A = R[in.a];
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
            case Op::DivRR: A = R[in.b] / R[in.c]; break;
            case Op::DivRK: A = R[in.b] / K[in.c]; break;
            case Op::DivKR: A = K[in.b] / R[in.c]; break;
            case Op::Sqr: A = sqr(R[in.b]); break;
            case Op::Sqrt: A = sqrt(R[in.b]); break;
            case Op::Exp: A = exp(R[in.b]); break;
            case Op::Log: A = log(R[in.b]); break;
            case Op::Sin: A = sin(R[in.b]); break;
            case Op::Cos: A = cos(R[in.b]); break;
            case Op::Abs: A = abs(R[in.b]); break;
            case Op::Sign: A = sign(R[in.b]); break;
            case Op::PowRR: A = pow(R[in.b], R[in.c]); break;
            case Op::PowRK: A = pow(R[in.b], T(K[in.c])); break;
            case Op::DerivU: A = DerivU(R[in.b]); break;
            case Op::DerivV: A = DerivV(R[in.b]); break;
        }
#ifdef AFFRAY_TRACE_VM
        std::fprintf(stderr, "[%s] %-40s -> %s\n", NumberTraits<T>::kName,
                     DisassembleInstr(*m_program, in).c_str(), ToString(A).c_str());
#endif
    }
}

}  // namespace affray::vm
