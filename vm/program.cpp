// vm/program.cpp: small queries on programs and globals.
#include "vm/program.h"

namespace affray::vm {

namespace {
struct GlobalInfo {
    const char* name;
    int size;
};
constexpr GlobalInfo kGlobalInfo[] = {
#define AFFRAY_GLOBAL_INFO(name, size) {#name, size},
    AFFRAY_GLOBALS(AFFRAY_GLOBAL_INFO)
#undef AFFRAY_GLOBAL_INFO
};
}  // namespace

const char* GlobalName(Global g) { return kGlobalInfo[static_cast<int>(g)].name; }
int GlobalSize(Global g) { return kGlobalInfo[static_cast<int>(g)].size; }

const ProgramOutput* Program::findOutput(const std::string& name) const {
    for (const ProgramOutput& o : outputs)
        if (o.name == name) return &o;
    return nullptr;
}

bool Program::usesDerivatives() const {
    for (const Instr& in : code)
        if (in.op == Op::DerivU || in.op == Op::DerivV) return true;
    return false;
}

}  // namespace affray::vm

namespace affray::vm {
Program IdentityProgram() {
    Program p;
    p.shaderName = "(none)";
    p.globalRegisters[static_cast<int>(Global::P)] = 0;
    p.globalRegisters[static_cast<int>(Global::N)] = 3;
    p.registerCount = 6;
    p.outputs.push_back({"P", 3, {0, 1, 2}});
    p.outputs.push_back({"N", 3, {3, 4, 5}});
    return p;
}
}  // namespace affray::vm
