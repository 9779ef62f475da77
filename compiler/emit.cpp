// compiler/emit.cpp: dead code elimination, instruction selection and register allocation.
// Node ids are already a topological order (an operand is always created before its user), so
// emission is one forward walk. Registers: globals the program reads are placed first (the
// caller writes them before the run); every other value takes the lowest free register when it
// is computed and gives it back after its last use.
#include "compiler/emit.h"

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
    void Push(vm::Op op, uint16_t a, uint16_t b, uint16_t c, int line) {
        m_out.code.push_back({op, 0, a, b, c});
        m_out.lines.push_back(line);
    }

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
        if (IsUnary(n.op)) use(n.a, false);
        if (IsBinary(n.op)) {
            // Every binary opcode has a K form for its second operand; Sub and Div also for the
            // first, Add and Mul commute. Only pow's base must be in a register.
            use(n.a, n.op != IrOp::Pow);
            use(n.b, true);
        }
    }
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
    auto isK = [&](ValueId x) { return m_ir.node(x).op == IrOp::Const && !m_register.count(x); };
    ValueId a = n.a, b = n.b;
    uint16_t ra = 0, rb = 0;
    bool binary = IsBinary(n.op);
    bool aK = isK(a), bK = binary && isK(b);
    if ((n.op == IrOp::Add || n.op == IrOp::Mul) && aK) {
        std::swap(a, b);
        std::swap(aK, bK);
    }
    ra = aK ? ConstantIndex(m_ir.node(a).k) : RegisterOf(a);
    if (binary) rb = bK ? ConstantIndex(m_ir.node(b).k) : RegisterOf(b);
    Release(a, v);
    if (binary && b != a) Release(b, v);
    uint16_t dst = Allocate();
    m_register[v] = dst;

    using vm::Op;
    Op op = Op::Move;
    switch (n.op) {
        case IrOp::Neg: op = Op::Neg; break;
        case IrOp::Sqr: op = Op::Sqr; break;
        case IrOp::Sqrt: op = Op::Sqrt; break;
        case IrOp::Exp: op = Op::Exp; break;
        case IrOp::Log: op = Op::Log; break;
        case IrOp::Sin: op = Op::Sin; break;
        case IrOp::Cos: op = Op::Cos; break;
        case IrOp::Abs: op = Op::Abs; break;
        case IrOp::Sign: op = Op::Sign; break;
        case IrOp::DerivU: op = Op::DerivU; break;
        case IrOp::DerivV: op = Op::DerivV; break;
        case IrOp::Add: op = bK ? Op::AddRK : Op::AddRR; break;
        case IrOp::Mul: op = bK ? Op::MulRK : Op::MulRR; break;
        case IrOp::Sub: op = aK ? Op::SubKR : bK ? Op::SubRK : Op::SubRR; break;
        case IrOp::Div: op = aK ? Op::DivKR : bK ? Op::DivRK : Op::DivRR; break;
        case IrOp::Pow: op = bK ? Op::PowRK : Op::PowRR; break;
        case IrOp::Const:
        case IrOp::Global:
        case IrOp::Param: break;
    }
    Push(op, dst, ra, rb, n.line);
}

void Emitter::Run(const std::vector<NamedValue>& outputs, const std::vector<vm::ProgramParam>& params) {
    MarkLive(outputs);

    // Globals first: a triple global gets three consecutive registers even if only one
    // component is live, because the caller writes all three.
    for (ValueId v = 0; v < m_ir.size(); ++v) {
        const IrNode& n = m_ir.node(v);
        if (!m_live[v] || n.op != IrOp::Global) continue;
        uint16_t& base = m_out.globalRegisters[n.a];
        if (base == vm::kNoRegister) {
            base = static_cast<uint16_t>(m_out.registerCount);
            m_out.registerCount += vm::GlobalSize(static_cast<vm::Global>(n.a));
        }
        m_register[v] = static_cast<uint16_t>(base + n.b);
    }
    // Parameters the outputs read: like globals, consecutive registers written before the run.
    m_out.params = params;
    for (vm::ProgramParam& p : m_out.params) p.firstRegister = vm::kNoRegister;
    for (ValueId v = 0; v < m_ir.size(); ++v) {
        const IrNode& n = m_ir.node(v);
        if (!m_live[v] || n.op != IrOp::Param) continue;
        vm::ProgramParam& p = m_out.params.at(n.a);
        if (p.firstRegister == vm::kNoRegister) {
            p.firstRegister = static_cast<uint16_t>(m_out.registerCount);
            m_out.registerCount += p.size;
        }
        m_register[v] = static_cast<uint16_t>(p.firstRegister + n.b);
    }
    for (size_t i = 0; i < m_out.params.size(); ++i) {
        const vm::ProgramParam& p = m_out.params[i];
        if (p.firstRegister == vm::kNoRegister) continue;
        for (int c = 0; c < p.size; ++c) {
            ValueId id = m_ir.Find(IrOp::Param, static_cast<uint32_t>(i), c);
            if (id == kNoValue || !m_live[id]) m_free.insert(static_cast<uint16_t>(p.firstRegister + c));
        }
    }
    // Components of read globals that nothing uses are free from the start.
    for (int g = 0; g < vm::kGlobalCount; ++g) {
        uint16_t base = m_out.globalRegisters[g];
        if (base == vm::kNoRegister) continue;
        for (int i = 0; i < vm::GlobalSize(static_cast<vm::Global>(g)); ++i) {
            ValueId id = m_ir.Find(IrOp::Global, g, i);
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
