// vm/interpreter_double.cpp: Interpreter<double>, instantiated from the one loop in interpreter.inl,
// and the scalar evaluation of one opcode that the constant folder uses.
#include <stdexcept>

#include "diag/check.h"
#include "vm/interpreter.inl"

namespace affray::vm {
template class Interpreter<double>;

double RunScalarOpcode(Op op, const double* operands, uint8_t flags) {
    const int n = OperandCount(op);
    // An all-register operation (a texture lookup needs its program's texture slots).
    AFFRAY_CHECK(FormOf(op) == OperandForm::RR && OperationOf(op) != Operation::None);
    AFFRAY_CHECK(OperationOf(op) != Operation::Texture);
    // R[i] := K[i] for each operand, then the opcode reading R[0..n-1] into R[n].
    Program program;
    program.constants.assign(operands, operands + n);
    program.registerCount = n + 1;
    for (int i = 0; i < n; ++i)
        program.code.push_back({Op::LoadK, 0, static_cast<uint16_t>(i), static_cast<uint16_t>(i), 0});
    const size_t first = program.code.size();
    program.code.resize(first + static_cast<size_t>(Words(op)), Instr{Op::Ext, 0, 0, 0, 0});
    Instr* in = &program.code[first];
    in->op = op;
    in->flags = flags;
    in->a = static_cast<uint16_t>(n);
    // Operand j is format letter j + 1: B, C, then the Ext words' A, B, C.
    for (int j = 0; j < n; ++j) {
        const int letter = j + 1;
        Instr& word = in[letter / 3];
        (letter % 3 == 0 ? word.a : letter % 3 == 1 ? word.b : word.c) = static_cast<uint16_t>(j);
    }
    program.lines.assign(program.code.size(), 0);
    Interpreter<double> interpreter(program);
    interpreter.Run();
    return interpreter.Register(n);
}

}  // namespace affray::vm
