// compiler/emit.cpp: dead code elimination, instruction selection and register allocation.
// Node ids are already a topological order (an operand is always created before its user), so
// emission is one forward walk. Registers: globals the program reads are placed first (the
// caller writes them before the run); every other value takes the lowest free register when it
// is computed and gives it back after its last use.
#include "compiler/emit.h"

#include "compiler/opcode_map.h"

#include <bit>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

namespace affray::compiler {

namespace {

constexpr size_t kForever = std::numeric_limits<size_t>::max();

class Emitter {
  public:
    Emitter(const IrBuilder& ir, vm::Program& out) : m_ir(ir), m_out(out) {}
    void Run(const std::vector<NamedValue>& outputs, const std::vector<vm::ProgramParam>& params);

  private:
    void MarkLive(const std::vector<NamedValue>& outputs);
    bool ConstInRegister(ValueId v) const { return m_constNeedsRegister.count(v) > 0; }
    uint16_t Allocate();
    void Release(ValueId v, size_t user);
    uint16_t ConstantIndex(double k);
    uint16_t RegisterOf(ValueId v) const { return m_register.at(v); }
    void EmitNode(ValueId v);
    void Push(vm::Op op, uint16_t a, uint16_t b, uint16_t c, int line, uint8_t flags = 0) {
        m_out.code.push_back({op, flags, a, b, c});
        m_out.lines.push_back(line);
    }
    /// The opcode for a node and which operands it takes as constants (swap: the operands of a
    /// commutative operation exchanged so that its constant comes second).
    struct Selection {
        vm::Op op = vm::Op::Move;
        bool aIsK = false, bIsK = false, swap = false;
    };
    Selection Select(const IrNode& n) const;

    const IrBuilder& m_ir;
    vm::Program& m_out;
    std::vector<bool> m_live;
    std::vector<size_t> m_lastUse;
    std::set<ValueId> m_constNeedsRegister;
    std::unordered_map<ValueId, uint16_t> m_register;
    std::set<uint16_t> m_free;
    std::unordered_map<uint64_t, uint16_t> m_constIndex;
};

void Emitter::MarkLive(const std::vector<NamedValue>& outputs) {
    m_live.assign(m_ir.size(), false);
    m_lastUse.assign(m_ir.size(), 0);
    std::vector<ValueId> stack;
    for (const NamedValue& o : outputs)
        for (int i = 0; i < o.value.size(); ++i) {
            stack.push_back(o.value.c[i]);
            m_lastUse[o.value.c[i]] = kForever;
            if (m_ir.node(o.value.c[i]).op == IrOp::Const) m_constNeedsRegister.insert(o.value.c[i]);
        }
    while (!stack.empty()) {
        ValueId v = stack.back();
        stack.pop_back();
        if (m_live[v]) continue;
        m_live[v] = true;
        const IrNode& n = m_ir.node(v);
        auto use = [&](ValueId operand, bool constantAllowed) {
            if (m_lastUse[operand] != kForever) m_lastUse[operand] = std::max<size_t>(m_lastUse[operand], v);
            if (m_ir.node(operand).op == IrOp::Const && !constantAllowed) m_constNeedsRegister.insert(operand);
            stack.push_back(operand);
        };
        const Selection s = Select(n);
        for (int i = 0; i < n.count; ++i) use(n.in[i], (i == 0 && s.aIsK) || (i == 1 && s.bIsK));
    }
}

Emitter::Selection Emitter::Select(const IrNode& n) const {
    Selection s;
    if (n.count == 0) return s;  // leaves are not instructions
    if (n.count != 2) {
        s.op = OpcodeFor(n.op, n.count, OperandForm::RR).value();
        return s;
    }
    auto isConst = [&](ValueId x) { return m_ir.node(x).op == IrOp::Const; };
    const bool aK = isConst(n.in[0]), bK = isConst(n.in[1]);
    if (bK)
        if (auto op = OpcodeFor(n.op, 2, OperandForm::RK)) {
            s.op = *op;
            s.bIsK = true;
            return s;
        }
    if (aK && IsCommutative(n.op))
        if (auto op = OpcodeFor(n.op, 2, OperandForm::RK)) {
            s.op = *op;
            s.aIsK = true;
            s.swap = true;
            return s;
        }
    if (aK)
        if (auto op = OpcodeFor(n.op, 2, OperandForm::KR)) {
            s.op = *op;
            s.aIsK = true;
            return s;
        }
    s.op = OpcodeFor(n.op, 2, OperandForm::RR).value();
    return s;
}

uint16_t Emitter::Allocate() {
    if (!m_free.empty()) {
        uint16_t r = *m_free.begin();
        m_free.erase(m_free.begin());
        return r;
    }
    if (m_out.registerCount >= vm::kMaxRegisters - 1)
        throw std::length_error("shader needs more than 65535 registers");
    return static_cast<uint16_t>(m_out.registerCount++);
}

void Emitter::Release(ValueId v, size_t user) {
    auto it = m_register.find(v);
    if (it != m_register.end() && m_lastUse[v] == user) m_free.insert(it->second);
}

uint16_t Emitter::ConstantIndex(double k) {
    auto [it, inserted] = m_constIndex.try_emplace(std::bit_cast<uint64_t>(k),
                                                   static_cast<uint16_t>(m_out.constants.size()));
    if (inserted) m_out.constants.push_back(k);
    return it->second;
}

void Emitter::EmitNode(ValueId v) {
    const IrNode& n = m_ir.node(v);
    if (n.op == IrOp::Global || n.op == IrOp::Param) return;  // placed up front
    if (n.op == IrOp::Const) {
        if (!ConstInRegister(v)) return;  // used as a K operand only
        uint16_t r = Allocate();
        m_register[v] = r;
        Push(vm::Op::LoadK, r, ConstantIndex(n.k), 0, n.line);
        return;
    }

    // Operand registers are read before the destination is written, so a register whose last
    // use is this instruction can be its destination.
    const Selection sel = Select(n);
    uint16_t operands[kMaxIrOperands] = {};
    for (int i = 0; i < n.count; ++i) {
        const bool isK = (i == 0 && sel.aIsK) || (i == 1 && sel.bIsK);
        operands[i] = isK ? ConstantIndex(m_ir.node(n.in[i]).k) : RegisterOf(n.in[i]);
    }
    if (sel.swap) std::swap(operands[0], operands[1]);
    for (int i = 0; i < n.count; ++i) {
        bool repeated = false;
        for (int j = 0; j < i; ++j) repeated = repeated || n.in[j] == n.in[i];
        if (!repeated) Release(n.in[i], v);
    }
    uint16_t dst = Allocate();
    m_register[v] = dst;

    // The operands fill B, C, then the Ext words' A, B, C (vm/opcodes.h).
    const int words = vm::Words(sel.op);
    uint16_t slots[9] = {dst};
    for (int i = 0; i < n.count; ++i) slots[i + 1] = operands[i];
    for (int w = 0; w < words; ++w)
        Push(w == 0 ? sel.op : vm::Op::Ext, slots[3 * w], slots[3 * w + 1], slots[3 * w + 2], n.line,
             w == 0 ? n.channel : 0);
}

void Emitter::Run(const std::vector<NamedValue>& outputs, const std::vector<vm::ProgramParam>& params) {
    MarkLive(outputs);

    // Globals first: a triple global gets three consecutive registers even if only one
    // component is live, because the caller writes all three.
    for (ValueId v = 0; v < m_ir.size(); ++v) {
        const IrNode& n = m_ir.node(v);
        if (!m_live[v] || n.op != IrOp::Global) continue;
        uint16_t& base = m_out.globalRegisters[n.in[0]];
        if (base == vm::kNoRegister) {
            base = static_cast<uint16_t>(m_out.registerCount);
            m_out.registerCount += vm::GlobalSize(static_cast<vm::Global>(n.in[0]));
        }
        m_register[v] = static_cast<uint16_t>(base + n.in[1]);
    }
    // Parameters the outputs read: like globals, consecutive registers written before the run.
    m_out.params = params;
    for (vm::ProgramParam& p : m_out.params) p.firstRegister = vm::kNoRegister;
    for (ValueId v = 0; v < m_ir.size(); ++v) {
        const IrNode& n = m_ir.node(v);
        if (!m_live[v] || n.op != IrOp::Param) continue;
        vm::ProgramParam& p = m_out.params.at(n.in[0]);
        if (p.firstRegister == vm::kNoRegister) {
            p.firstRegister = static_cast<uint16_t>(m_out.registerCount);
            m_out.registerCount += p.size;
        }
        m_register[v] = static_cast<uint16_t>(p.firstRegister + n.in[1]);
    }
    for (size_t i = 0; i < m_out.params.size(); ++i) {
        const vm::ProgramParam& p = m_out.params[i];
        if (p.firstRegister == vm::kNoRegister) continue;
        for (int c = 0; c < p.size; ++c) {
            ValueId id = m_ir.FindLeaf(IrOp::Param, static_cast<uint32_t>(i), c);
            if (id == kNoValue || !m_live[id]) m_free.insert(static_cast<uint16_t>(p.firstRegister + c));
        }
    }
    // Components of read globals that nothing uses are free from the start.
    for (int g = 0; g < vm::kGlobalCount; ++g) {
        uint16_t base = m_out.globalRegisters[g];
        if (base == vm::kNoRegister) continue;
        for (int i = 0; i < vm::GlobalSize(static_cast<vm::Global>(g)); ++i) {
            ValueId id = m_ir.FindLeaf(IrOp::Global, g, i);
            if (id == kNoValue || !m_live[id]) m_free.insert(static_cast<uint16_t>(base + i));
        }
    }

    for (ValueId v = 0; v < m_ir.size(); ++v)
        if (m_live[v]) EmitNode(v);

    for (const NamedValue& o : outputs) {
        vm::ProgramOutput out;
        out.name = o.name;
        out.size = o.value.size();
        for (int i = 0; i < out.size; ++i) out.registers[i] = RegisterOf(o.value.c[i]);
        m_out.outputs.push_back(out);
    }
}

}  // namespace

vm::Program Emit(const IrBuilder& ir, const std::vector<NamedValue>& outputs,
                 const std::vector<vm::ProgramParam>& params) {
    vm::Program program;
    Emitter emitter(ir, program);
    emitter.Run(outputs, params);
    return program;
}

}  // namespace affray::compiler
