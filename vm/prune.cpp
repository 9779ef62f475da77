// vm/prune.cpp: Prune: value numbering here, then the back end every program writer shares
// (vm/assemble.h: liveness from the outputs, registers, the constant pool).
// Value numbering, forward: each register holds a value (an input, or the result of an
// operation); an instruction the decisions make a copy of an operand (a decided Select, Min or
// Max, or a Move) only renames, one with a constant result becomes a LoadK, and a register operand
// holding a constant becomes a constant operand where the opcode has that form.
// Why the scalar results stay the same bit for bit: every kept instruction computes the same
// double operation on the same operand values (renaming changes no value, R + K[c] is the same
// double operation as R + R[c] with R[c] = K[c]), and a dropped one is replaced by the operand or
// constant the decisions proved it gives.
#include "vm/prune.h"
#include "diag/check.h"

#include <climits>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace affray::vm {

bool SlopesCanBound(const Program& program) {
    for (size_t pc = 0; pc < program.code.size(); pc += Words(program.code[pc].op)) {
        const Operation f = OperationOf(program.code[pc].op);
        if (Has(f, kDerivative) || Has(f, kPointwiseSlope)) return false;
    }
    return true;
}

bool HasJumps(const Program& program) {
    for (size_t pc = 0; pc < program.code.size(); pc += Words(program.code[pc].op))
        if (Has(OperationOf(program.code[pc].op), kJumps)) return true;
    return false;
}

bool JumpsDecided(const Program& program, const Decisions& decisions) {
    if (decisions.size() != program.code.size()) return false;
    for (size_t pc = 0; pc < program.code.size(); pc += Words(program.code[pc].op)) {
        if (!Has(OperationOf(program.code[pc].op), kJumps)) continue;
        double c;
        if (decisions.operandAt(pc) == 0 && !decisions.constantAt(pc, &c)) return false;
    }
    return true;
}

size_t Decisions::usefulCount(const Program& program) const {
    size_t n = 0;
    for (size_t pc = 0; pc < program.code.size() && pc < size(); pc += Words(program.code[pc].op)) {
        double c;
        if (m_operand[pc] != 0 || (program.code[pc].op != Op::LoadK && constantAt(pc, &c))) ++n;
    }
    return n;
}

std::string Decisions::ToString() const {
    std::string s;
    char buf[64];
    for (size_t pc = 0; pc < size(); ++pc) {
        double c;
        if (m_operand[pc] != 0) {
            std::snprintf(buf, sizeof buf, "%zu: operand %c\n", pc, "ABCD"[m_operand[pc] & 3]);
            s += buf;
        }
        if (constantAt(pc, &c)) {
            std::snprintf(buf, sizeof buf, "%zu: = %.17g\n", pc, c);
            s += buf;
        }
    }
    return s;
}

void Pruner::Prune(const Program& program, const Decisions& decisions, Program* out) {
    // The decisions must have been recorded for this program.
    AFFRAY_CHECK_EQ(decisions.size(), program.code.size());
    Assembler& as = m_assembler;
    as.Clear();
    m_regValue.assign(program.registerCount, -1);
    m_valueConstant.clear();
    auto known = [&](int v) { return v < static_cast<int>(m_valueConstant.size()) && !std::isnan(m_valueConstant[v]); };
    auto remember = [&](int v, double k) {
        if (static_cast<int>(m_valueConstant.size()) <= v) m_valueConstant.resize(v + 1, Decisions::kNone);
        m_valueConstant[v] = k;
    };

    // Inputs: the registers the caller writes before a run.
    for (int g = 0; g < kGlobalCount; ++g) {
        const uint16_t base = program.globalRegisters[g];
        if (base == kNoRegister) continue;
        const int first = as.Global(static_cast<Global>(g));
        for (int i = 0; i < GlobalSize(static_cast<Global>(g)); ++i) m_regValue[base + i] = first + i;
    }
    for (size_t p = 0; p < program.params.size(); ++p) {
        const ProgramParam& param = program.params[p];
        if (param.firstRegister == kNoRegister) continue;
        const int first = as.Param(p, param.size);
        for (int i = 0; i < param.size; ++i) m_regValue[param.firstRegister + i] = first + i;
    }

    // Value numbering. Constant forms only where the program takes no derivatives: for dual
    // numbers R + K[c] and R + R[c] may differ in the sign of a zero derivative, which Du or Dv
    // would carry into values.
    const bool constantForms = !program.usesDerivatives();
    auto lineAt = [&](size_t pc) { return program.lines.empty() ? 0 : program.lines[pc]; };
    auto load = [&](size_t pc, double k) {
        const int v = as.Load(k, lineAt(pc));
        remember(v, k);
        return v;
    };
    for (size_t pc = 0; pc < program.code.size(); pc += Words(program.code[pc].op)) {
        const Instr* in = &program.code[pc];
        const char* format = Info(in->op).format;
        const int operand = decisions.operandAt(pc);
        double k;
        if (decisions.constantAt(pc, &k) && in->op != Op::LoadK) {
            m_regValue[in->a] = load(pc, k);
        } else if (in->op == Op::LoadK) {
            m_regValue[in->a] = load(pc, program.constants[in->b]);
        } else if (in->op == Op::Move) {
            m_regValue[in->a] = m_regValue[in->b];
        } else if (operand > 0 && format[operand] == 'r') {
            m_regValue[in->a] = m_regValue[OperandOf(in, operand)];
        } else if (operand > 0 && format[operand] == 'k') {
            m_regValue[in->a] = load(pc, program.constants[OperandOf(in, operand)]);
        } else {
            Op op = in->op;
            int operands[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
            for (int i = 1; format[i]; ++i) {
                const uint16_t x = OperandOf(in, i);
                if (format[i] == 'r')
                    operands[i - 1] = m_regValue[x];
                else if (format[i] == 'k')
                    operands[i - 1] = as.Constant(program.constants[x]);
            }
            // A register operand now known to be a constant: R op R[c] => R op K[c].
            for (int i = 1; i <= 2 && constantForms; ++i) {
                if (format[i] != 'r' || !known(operands[i - 1])) continue;
                const Op form = ConstantFormOf(in->op, i);
                const double c = m_valueConstant[operands[i - 1]];
                // A NaN constant would make the commuted operations differ in the NaN they give.
                if (form == Op::Ext || std::isnan(c)) continue;
                const int reg = operands[2 - i], slot = as.Constant(c);
                const bool constantFirst = Info(form).format[1] == 'k';
                op = form;
                operands[0] = constantFirst ? slot : reg;
                operands[1] = constantFirst ? reg : slot;
                break;
            }
            m_regValue[in->a] = as.Operation(op, operands, lineAt(pc), in->flags);
        }
    }

    // Liveness, registers and code: the shared back end.
    std::vector<Assembler::Output> outputs;
    for (const ProgramOutput& o : program.outputs) {
        Assembler::Output x;
        x.name = o.name;
        x.size = o.size;
        for (int i = 0; i < o.size; ++i) x.values[i] = m_regValue[o.registers[i]];
        outputs.push_back(x);
    }
    out->shaderName = program.shaderName;
    out->sourcePath = program.sourcePath;
    out->spaces = program.spaces;
    out->textures = program.textures;
    as.Finish(outputs, program.params, !program.lines.empty(), out);
}

Program Prune(const Program& program, const Decisions& decisions) {
    Program out;
    Pruner().Prune(program, decisions, &out);
    return out;
}

}  // namespace affray::vm
