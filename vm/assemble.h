// vm/assemble.h: the one back end that writes programs: from straight-line operations over values
// to register code. The compiler's emitter (compiler/emit.cpp) and the per-region pruner
// (vm/prune.cpp) both describe their code as operations on values and leave the rest to it:
//  1. liveness, backward from the outputs: operations no output needs are dropped;
//  2. inputs: a global or parameter that a live operation reads keeps a block of registers (the
//     caller writes all its components); one nothing reads gets kNoRegister;
//  3. registers, forward: each result takes the lowest register free at that point, where an
//     operand read for the last time is freed first (an instruction reads before it writes);
//  4. the constant pool keeps, once each, the constants the kept code reads.
#pragma once

#include <cstdint>
#include <vector>

#include "vm/program.h"

namespace affray::vm {

class Assembler {
  public:
    /// Value ids, in creation order: inputs and operation results.
    using ValueId = int;

    /// The values of the components of global `g` (GlobalSize(g) consecutive ids from the one
    /// returned), as the caller writes them before a run.
    ValueId Global(vm::Global g);
    /// The values of parameter `index` of `params` (Finish), `size` consecutive ids.
    ValueId Param(size_t index, int size);
    /// A constant operand ('k'), by value.
    int Constant(double k);
    /// Appends `op` with its operands, one per 'r' or 'k' letter of its format after A (a value
    /// for 'r', a Constant for 'k'), and returns its result. Operands must exist already.
    ValueId Operation(Op op, const int* operands, int line, uint8_t flags = 0);
    /// K[c] in a register (a LoadK), once per constant value.
    ValueId Load(double k, int line);

    struct Output {
        std::string name;
        int size = 3;
        ValueId values[3] = {-1, -1, -1};
    };
    /// Writes the code computing `outputs` into *out (its code, lines, constants, registerCount,
    /// globalRegisters, params and outputs; other fields are left as they are). `params` describe
    /// the Param inputs by index. With `lines`, out->lines gets each word's source line.
    void Finish(const std::vector<Output>& outputs, const std::vector<ProgramParam>& params, bool lines, Program* out);

    /// Forgets everything (keeping the capacity), for another program.
    void Clear();

  private:
    struct Value {
        int input = -1;     // for an input: its global (0..) or kGlobalCount + parameter index
        int component = 0;  // for an input: which component
        int lastUse = -1;   // the last live operation reading it (INT_MAX for an output)
        uint16_t reg = kNoRegister;
    };
    struct Node {
        Op op;
        uint8_t flags;
        int line;
        ValueId result;
        int operands[8];
        bool live;
    };

    std::vector<Value> m_values;
    std::vector<Node> m_nodes;
    std::vector<double> m_constants;
    std::vector<std::pair<uint64_t, ValueId>> m_loads;  // LoadK results by constant bits
    std::vector<std::pair<int, ValueId>> m_inputs;      // first value of each input block
};

}  // namespace affray::vm
