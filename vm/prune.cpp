// vm/prune.cpp: Prune, in three passes over the straight-line code.
//  1. Forward, value numbering: each register holds a value (an input, or the result of a node);
//     an instruction the decisions make a copy of an operand (a decided Select, Min or Max, or a
//     Move) only renames, one with a constant result becomes a LoadK node, and a register operand
//     holding a constant becomes a constant operand where the opcode has that form.
//  2. Backward, liveness from the outputs: nodes no output needs are dropped.
//  3. Forward, registers: globals and parameters read get blocks of their own, then each node's
//     result takes a register freed by a value past its last use (its own operands' included:
//     an instruction reads before it writes).
// Why the scalar results stay the same bit for bit: every kept instruction computes the same
// double operation on the same operand values (renaming changes no value, R + K[c] is the same
// double operation as R + R[c] with R[c] = K[c]), and a dropped one is replaced by the operand or
// constant the decisions proved it gives.
#include "vm/prune.h"

#include <climits>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace affray::vm {

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

int Pruner::NewValue() {
    m_values.push_back(Value{});
    return static_cast<int>(m_values.size()) - 1;
}

int Pruner::ConstantSlot(double k) {
    m_slots.push_back(k);
    return static_cast<int>(m_slots.size()) - 1;
}

void Pruner::Prune(const Program& program, const Decisions& decisions, Program* out) {
    if (decisions.size() != program.code.size())
        throw std::logic_error("Prune: the decisions were recorded for another program");
    m_values.clear();
    m_nodes.clear();
    m_slots.clear();
    m_regValue.assign(program.registerCount, -1);
    m_originalSlot.assign(program.constants.size(), -1);
    auto originalSlot = [&](uint16_t k) {
        if (m_originalSlot[k] < 0) m_originalSlot[k] = ConstantSlot(program.constants[k]);
        return m_originalSlot[k];
    };

    // Inputs: the registers the caller writes before a run.
    for (int g = 0; g < kGlobalCount; ++g) {
        const uint16_t base = program.globalRegisters[g];
        if (base == kNoRegister) continue;
        for (int i = 0; i < GlobalSize(static_cast<Global>(g)); ++i) m_regValue[base + i] = NewValue();
    }
    for (const ProgramParam& p : program.params) {
        if (p.firstRegister == kNoRegister) continue;
        for (int i = 0; i < p.size; ++i) m_regValue[p.firstRegister + i] = NewValue();
    }

    // 1. Value numbering. Constant forms only where the program takes no derivatives: for dual
    // numbers R + K[c] and R + R[c] may differ in the sign of a zero derivative, which Du or Dv
    // would carry into values.
    const bool constantForms = !program.usesDerivatives();
    auto addNode = [&](Op op, uint8_t flags, size_t pc) {
        Node n{};
        n.op = op;
        n.flags = flags;
        n.line = program.lines.empty() ? 0 : program.lines[pc];
        n.result = NewValue();
        for (int& o : n.operands) o = -1;
        m_nodes.push_back(n);
        return static_cast<int>(m_nodes.size()) - 1;
    };
    auto loadConstant = [&](size_t pc, int slot) {
        const int node = addNode(Op::LoadK, 0, pc);
        m_nodes[node].operands[0] = slot;
        Value& v = m_values[m_nodes[node].result];
        v.constant = true;
        v.slot = slot;
        return m_nodes[node].result;
    };
    for (size_t pc = 0; pc < program.code.size(); pc += Words(program.code[pc].op)) {
        const Instr* in = &program.code[pc];
        const char* format = Info(in->op).format;
        const int operand = decisions.operandAt(pc);
        double k;
        if (decisions.constantAt(pc, &k) && in->op != Op::LoadK) {
            m_regValue[in->a] = loadConstant(pc, ConstantSlot(k));
        } else if (in->op == Op::LoadK) {
            m_regValue[in->a] = loadConstant(pc, originalSlot(in->b));
        } else if (in->op == Op::Move) {
            m_regValue[in->a] = m_regValue[in->b];
        } else if (operand > 0 && format[operand] == 'r') {
            m_regValue[in->a] = m_regValue[OperandOf(in, operand)];
        } else if (operand > 0 && format[operand] == 'k') {
            m_regValue[in->a] = loadConstant(pc, originalSlot(OperandOf(in, operand)));
        } else {
            const int node = addNode(in->op, in->flags, pc);
            Node& n = m_nodes[node];
            for (int i = 1; format[i]; ++i) {
                const uint16_t x = OperandOf(in, i);
                n.operands[i - 1] = format[i] == 'r' ? m_regValue[x] : format[i] == 'k' ? originalSlot(x) : -1;
            }
            // A register operand now known to be a constant: R op R[c] => R op K[c].
            for (int i = 1; i <= 2 && constantForms; ++i) {
                if (format[i] != 'r' || !m_values[n.operands[i - 1]].constant) continue;
                const Op form = ConstantFormOf(in->op, i);
                const int slot = m_values[n.operands[i - 1]].slot;
                // A NaN constant would make the commuted operations differ in the NaN they give.
                if (form == Op::Ext || std::isnan(m_slots[slot])) continue;
                const int reg = n.operands[2 - i];
                const bool constantFirst = Info(form).format[1] == 'k';
                n.op = form;
                n.operands[0] = constantFirst ? slot : reg;
                n.operands[1] = constantFirst ? reg : slot;
                break;
            }
            m_regValue[in->a] = n.result;
        }
    }

    // 2. Liveness, from the outputs back.
    std::vector<char>& used = m_used;  // per value: read by a live node or an output
    used.assign(m_values.size(), 0);
    for (const ProgramOutput& o : program.outputs)
        for (int i = 0; i < o.size; ++i) {
            const int v = m_regValue[o.registers[i]];
            used[v] = 1;
            m_values[v].lastUse = INT_MAX;
        }
    for (int j = static_cast<int>(m_nodes.size()) - 1; j >= 0; --j) {
        Node& n = m_nodes[j];
        n.live = used[n.result];
        if (!n.live) continue;
        const char* format = Info(n.op).format;
        for (int i = 1; format[i]; ++i)
            if (format[i] == 'r') used[n.operands[i - 1]] = 1;
    }

    // 3. Registers and code.
    out->shaderName = program.shaderName;
    out->sourcePath = program.sourcePath;
    out->spaces = program.spaces;
    out->code.clear();
    out->lines.clear();
    out->constants.clear();
    m_slotIndex.assign(m_slots.size(), -1);
    int nRegs = 0;
    m_free.clear();
    for (int j = 0; j < static_cast<int>(m_nodes.size()); ++j) {
        const Node& n = m_nodes[j];
        if (!n.live) continue;
        const char* format = Info(n.op).format;
        for (int i = 1; format[i]; ++i)
            if (format[i] == 'r' && m_values[n.operands[i - 1]].lastUse != INT_MAX)
                m_values[n.operands[i - 1]].lastUse = j;
    }
    // A global or parameter any live value reads keeps a block of registers (the caller writes
    // all its components); one no longer read is no longer computed. The inputs' values are the
    // first ones, numbered in this order above.
    int input = 0;
    auto placeInput = [&](uint16_t* base, int size) {
        bool read = false;
        for (int i = 0; i < size; ++i) read = read || used[input + i];
        if (!read) {
            input += size;
            *base = kNoRegister;
            return;
        }
        *base = static_cast<uint16_t>(nRegs);
        for (int i = 0; i < size; ++i, ++input) {
            m_values[input].reg = static_cast<uint16_t>(nRegs++);
            // A component never read is free for other values from the start.
            if (!used[input]) m_free.push_back(m_values[input].reg);
        }
    };
    out->globalRegisters = program.globalRegisters;
    for (int g = 0; g < kGlobalCount; ++g)
        if (out->globalRegisters[g] != kNoRegister) placeInput(&out->globalRegisters[g], GlobalSize(static_cast<Global>(g)));
    out->params = program.params;
    for (ProgramParam& p : out->params)
        if (p.firstRegister != kNoRegister) placeInput(&p.firstRegister, p.size);

    for (int j = 0; j < static_cast<int>(m_nodes.size()); ++j) {
        const Node& n = m_nodes[j];
        if (!n.live) continue;
        const char* format = Info(n.op).format;
        // Free the operands read for the last time, so the result may take one of them.
        for (int i = 1; format[i]; ++i) {
            if (format[i] != 'r') continue;
            Value& v = m_values[n.operands[i - 1]];
            if (v.lastUse == j) {
                m_free.push_back(v.reg);
                v.lastUse = -1;  // freed once, even if read twice
            }
        }
        Value& result = m_values[n.result];
        if (!m_free.empty()) {
            result.reg = m_free.back();
            m_free.pop_back();
        } else {
            result.reg = static_cast<uint16_t>(nRegs++);
        }
        // Emit, the operands filling B, C, then the Ext words' A, B, C.
        const int words = WordCount(format);
        uint16_t slots[9] = {result.reg};
        for (int i = 1; format[i]; ++i) {
            const int x = n.operands[i - 1];
            if (format[i] == 'r') {
                slots[i] = m_values[x].reg;
            } else if (format[i] == 'k') {
                if (m_slotIndex[x] < 0) {
                    m_slotIndex[x] = static_cast<int>(out->constants.size());
                    out->constants.push_back(m_slots[x]);
                }
                slots[i] = static_cast<uint16_t>(m_slotIndex[x]);
            }
        }
        for (int w = 0; w < words; ++w) {
            out->code.push_back(Instr{w == 0 ? n.op : Op::Ext, w == 0 ? n.flags : uint8_t(0), slots[3 * w],
                                      slots[3 * w + 1], slots[3 * w + 2]});
            if (!program.lines.empty()) out->lines.push_back(n.line);
        }
    }
    out->registerCount = nRegs;

    out->outputs = program.outputs;
    for (size_t o = 0; o < out->outputs.size(); ++o)
        for (int i = 0; i < out->outputs[o].size; ++i)
            out->outputs[o].registers[i] = m_values[m_regValue[program.outputs[o].registers[i]]].reg;
}

Program Prune(const Program& program, const Decisions& decisions) {
    Program out;
    Pruner().Prune(program, decisions, &out);
    return out;
}

}  // namespace affray::vm
