// vm/assemble.cpp: liveness, input placement, register allocation and emission (see the header).
#include "vm/assemble.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace affray::vm {

namespace {

/// Whether format letter `i` (after A) of `op` reads a register.
bool ReadsRegister(const char* format, int i) { return format[i] == 'r'; }

}  // namespace

void Assembler::Clear() {
    m_values.clear();
    m_nodes.clear();
    m_constants.clear();
    m_loads.clear();
    m_inputs.clear();
}

Assembler::ValueId Assembler::Global(vm::Global g) {
    const int key = static_cast<int>(g);
    for (const auto& [input, first] : m_inputs)
        if (input == key) return first;
    const ValueId first = static_cast<ValueId>(m_values.size());
    for (int i = 0; i < GlobalSize(g); ++i) m_values.push_back(Value{key, i});
    m_inputs.emplace_back(key, first);
    return first;
}

Assembler::ValueId Assembler::Param(size_t index, int size) {
    const int key = kGlobalCount + static_cast<int>(index);
    for (const auto& [input, first] : m_inputs)
        if (input == key) return first;
    const ValueId first = static_cast<ValueId>(m_values.size());
    for (int i = 0; i < size; ++i) m_values.push_back(Value{key, i});
    m_inputs.emplace_back(key, first);
    return first;
}

int Assembler::Constant(double k) {
    m_constants.push_back(k);
    return static_cast<int>(m_constants.size()) - 1;
}

Assembler::ValueId Assembler::Operation(Op op, const int* operands, int line, uint8_t flags) {
    Node n{op, flags, line, static_cast<ValueId>(m_values.size()), {-1, -1, -1, -1, -1, -1, -1, -1}, false};
    const char* format = Info(op).format;
    for (int i = 1; format[i]; ++i)
        if (format[i] == 'r' || format[i] == 'k') n.operands[i - 1] = operands[i - 1];
    m_values.push_back(Value{});
    m_nodes.push_back(n);
    return n.result;
}

Assembler::ValueId Assembler::Load(double k, int line) {
    const uint64_t bits = std::bit_cast<uint64_t>(k);
    for (const auto& [b, v] : m_loads)
        if (b == bits) return v;
    const int slot = Constant(k);
    const ValueId v = Operation(Op::LoadK, &slot, line);
    m_loads.emplace_back(bits, v);
    return v;
}

void Assembler::Finish(const std::vector<Output>& outputs, const std::vector<ProgramParam>& params, bool lines,
                       Program* out) {
    // 1. Liveness, from the outputs back.
    std::vector<char> used(m_values.size(), 0);
    for (const Output& o : outputs)
        for (int i = 0; i < o.size; ++i) {
            used[o.values[i]] = 1;
            m_values[o.values[i]].lastUse = INT_MAX;
        }
    for (int j = static_cast<int>(m_nodes.size()) - 1; j >= 0; --j) {
        Node& n = m_nodes[j];
        n.live = used[n.result];
        if (!n.live) continue;
        const char* format = Info(n.op).format;
        for (int i = 1; format[i]; ++i)
            if (ReadsRegister(format, i)) used[n.operands[i - 1]] = 1;
    }
    for (int j = 0; j < static_cast<int>(m_nodes.size()); ++j) {
        const Node& n = m_nodes[j];
        if (!n.live) continue;
        const char* format = Info(n.op).format;
        for (int i = 1; format[i]; ++i)
            if (ReadsRegister(format, i) && m_values[n.operands[i - 1]].lastUse != INT_MAX)
                m_values[n.operands[i - 1]].lastUse = j;
    }

    // 2. Inputs: globals by number, then parameters by index, a block each if anything reads them.
    out->code.clear();
    out->lines.clear();
    out->constants.clear();
    out->outputs.clear();
    out->globalRegisters.fill(kNoRegister);
    out->params = params;
    for (ProgramParam& p : out->params) p.firstRegister = kNoRegister;
    int nRegs = 0;
    std::set<uint16_t> free;
    std::sort(m_inputs.begin(), m_inputs.end());
    for (const auto& [input, first] : m_inputs) {
        const int size =
            input < kGlobalCount ? GlobalSize(static_cast<vm::Global>(input)) : params.at(input - kGlobalCount).size;
        bool read = false;
        for (int i = 0; i < size; ++i) read = read || used[first + i];
        if (!read) continue;
        const uint16_t base = static_cast<uint16_t>(nRegs);
        if (input < kGlobalCount)
            out->globalRegisters[input] = base;
        else
            out->params[input - kGlobalCount].firstRegister = base;
        for (int i = 0; i < size; ++i) {
            m_values[first + i].reg = static_cast<uint16_t>(nRegs++);
            // A component nothing reads is free for other values from the start.
            if (!used[first + i]) free.insert(m_values[first + i].reg);
        }
    }

    // 3. Registers and code, forward.
    std::unordered_map<uint64_t, uint16_t> pool;  // constant bits -> index in out->constants
    for (int j = 0; j < static_cast<int>(m_nodes.size()); ++j) {
        const Node& n = m_nodes[j];
        if (!n.live) continue;
        const char* format = Info(n.op).format;
        // Free the operands read for the last time, so that the result may take one of them.
        for (int i = 1; format[i]; ++i) {
            if (!ReadsRegister(format, i)) continue;
            Value& v = m_values[n.operands[i - 1]];
            if (v.lastUse == j) {
                free.insert(v.reg);
                v.lastUse = -1;  // freed once, even if read twice
            }
        }
        Value& result = m_values[n.result];
        if (!free.empty()) {
            result.reg = *free.begin();
            free.erase(free.begin());
        } else {
            if (nRegs >= kMaxRegisters - 1) throw std::length_error("shader needs more than 65535 registers");
            result.reg = static_cast<uint16_t>(nRegs++);
        }
        // The operands fill B, C, then the Ext words' A, B, C (vm/opcodes.h).
        uint16_t slots[9] = {result.reg};
        for (int i = 1; format[i]; ++i) {
            const int x = n.operands[i - 1];
            if (format[i] == 'r') {
                slots[i] = m_values[x].reg;
            } else if (format[i] == 'k') {
                const double k = m_constants[x];
                auto [it, inserted] =
                    pool.try_emplace(std::bit_cast<uint64_t>(k), static_cast<uint16_t>(out->constants.size()));
                if (inserted) {
                    if (out->constants.size() >= size_t(kMaxConstants))
                        throw std::length_error("shader needs more than 65536 constants");
                    out->constants.push_back(k);
                }
                slots[i] = it->second;
            }
        }
        const int words = Words(n.op);
        for (size_t w = 0; w < size_t(words); ++w) {
            out->code.push_back(Instr{w == 0 ? n.op : Op::Ext, w == 0 ? n.flags : uint8_t(0), slots[3 * w],
                                      slots[3 * w + 1], slots[3 * w + 2]});
            if (lines) out->lines.push_back(n.line);
        }
    }
    out->registerCount = nRegs;

    for (const Output& o : outputs) {
        ProgramOutput p;
        p.name = o.name;
        p.size = o.size;
        for (int i = 0; i < o.size; ++i) p.registers[i] = m_values[o.values[i]].reg;
        out->outputs.push_back(p);
    }
}

}  // namespace affray::vm
