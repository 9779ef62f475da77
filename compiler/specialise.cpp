// compiler/specialise.cpp: lift a generic program back into the value graph with its parameters
// replaced by constants, then emit it again. Lifting walks the straight-line code once, keeping
// for each register the IR node it holds; the IR builder folds and shares as the nodes are
// created, and emission drops what the outputs no longer need.
#include "compiler/specialise.h"

#include <cmath>

#include "compiler/emit.h"
#include "compiler/opcode_map.h"

namespace affray::compiler {

namespace {

bool BindValues(const vm::Program& program, const std::vector<ParamOverride>& overrides,
                std::vector<std::vector<double>>* values, std::vector<std::string>* errors) {
    const std::string shader = "shader '" + program.shaderName + "'";
    for (const vm::ProgramParam& p : program.params) values->push_back(p.defaults);
    bool ok = true;
    for (const ParamOverride& o : overrides) {
        size_t i = 0;
        while (i < program.params.size() && program.params[i].name != o.name) ++i;
        if (i == program.params.size()) {
            errors->push_back(shader + " has no parameter '" + o.name + "'");
            ok = false;
            continue;
        }
        const vm::ProgramParam& p = program.params[i];
        size_t want = static_cast<size_t>(p.size);
        // One number stands for a triple of three equal components, or for a matrix x * identity.
        const bool isArray = p.type.find('[') != std::string::npos;
        const bool promoted = o.numbers.size() == 1 && !isArray && (want == 3 || want == 16);
        if (o.numbers.size() != want && !promoted) {
            errors->push_back("parameter '" + o.name + "' of " + shader + " is a " + p.type + " and takes " +
                              std::to_string(want) + " value" + (want == 1 ? "" : "s") + ", got " +
                              std::to_string(o.numbers.size()));
            ok = false;
            continue;
        }
        bool finite = true;
        for (double x : o.numbers) finite = finite && std::isfinite(x);
        if (!finite) {
            errors->push_back("parameter '" + o.name + "' of " + shader + " must be finite (got NaN or infinity)");
            ok = false;
            continue;
        }
        for (size_t c = 0; c < want; ++c)
            (*values)[i][c] = !promoted ? o.numbers[c] : want == 16 && c % 5 != 0 ? 0.0 : o.numbers[0];
    }
    return ok;
}

}  // namespace

std::optional<std::vector<std::vector<double>>> BindParameters(const vm::Program& program,
                                                               const std::vector<ParamOverride>& overrides,
                                                               std::vector<std::string>* errors) {
    std::vector<std::vector<double>> values;
    if (!BindValues(program, overrides, &values, errors)) return std::nullopt;
    return values;
}

std::optional<vm::Program> Specialise(const vm::Program& program, const std::vector<ParamOverride>& overrides,
                                      std::vector<std::string>* errors,
                                      const std::vector<ConstantGlobal>& constantGlobals) {
    std::vector<std::vector<double>> values;
    if (!BindValues(program, overrides, &values, errors)) return std::nullopt;

    IrBuilder ir;
    std::vector<ValueId> reg(program.registerCount, kNoValue);
    for (int g = 0; g < vm::kGlobalCount; ++g) {
        uint16_t base = program.globalRegisters[g];
        if (base == vm::kNoRegister) continue;
        for (int i = 0; i < vm::GlobalSize(static_cast<vm::Global>(g)); ++i)
            reg[base + i] = ir.Global(static_cast<vm::Global>(g), i);
    }
    for (const ConstantGlobal& c : constantGlobals) {
        uint16_t base = program.globalRegisters[static_cast<int>(c.global)];
        if (base == vm::kNoRegister) continue;
        for (int i = 0; i < vm::GlobalSize(c.global); ++i) reg[base + i] = ir.Const(c.value[i]);
    }
    for (size_t p = 0; p < program.params.size(); ++p) {
        const vm::ProgramParam& param = program.params[p];
        if (param.firstRegister == vm::kNoRegister) continue;
        for (int i = 0; i < param.size; ++i) reg[param.firstRegister + i] = ir.Const(values[p][i]);
    }

    const std::vector<double>& K = program.constants;
    for (size_t pc = 0; pc < program.code.size(); pc += vm::Words(program.code[pc].op)) {
        const vm::Instr& in = program.code[pc];
        const int line = pc < program.lines.size() ? program.lines[pc] : 0;
        const char* format = vm::Info(in.op).format;
        // Operand i of the IR node is format letter i + 1 (letter 0 is the destination).
        auto operand = [&](int i) {
            uint16_t x = vm::OperandOf(&in, i + 1);
            return format[i + 1] == 'k' ? ir.Const(K[x]) : reg[x];
        };
        ValueId v = kNoValue;
        if (in.op == vm::Op::LoadK) {
            v = ir.Const(K[in.b]);
        } else if (in.op == vm::Op::Move) {
            v = reg[in.b];
        } else {
            const OpcodeRow* row = RowOf(in.op);
            IrNode n;
            n.op = row->ir;
            n.count = static_cast<uint8_t>(row->count);
            n.channel = in.flags;
            n.line = line;
            for (int i = 0; i < row->count; ++i) n.in[i] = operand(i);
            v = ir.Create(n);
        }
        reg[in.a] = v;
    }

    std::vector<NamedValue> outputs;
    for (const vm::ProgramOutput& o : program.outputs) {
        Value value;
        value.type = o.size == 1 ? Type::Float : Type::Point;
        for (int i = 0; i < o.size; ++i) value.c[i] = reg[o.registers[i]];
        if (o.size == 1) value.c[1] = value.c[2] = value.c[0];
        outputs.push_back({o.name, value});
    }
    vm::Program out = Emit(ir, outputs);
    for (double k : out.constants) {
        if (IsParameterLoopPoison(k)) {
            errors->push_back("shader '" + program.shaderName +
                              "': with these parameter values a loop runs longer "
                              "than the compiled program was unrolled for; use the shader's source (.sl), which is "
                              "unrolled for each instance's values");
            return std::nullopt;
        }
    }
    out.shaderName = program.shaderName;
    out.sourcePath = program.sourcePath;
    out.textures = program.textures;
    return out;
}

}  // namespace affray::compiler
