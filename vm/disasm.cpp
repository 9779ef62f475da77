// vm/disasm.cpp: the disassembler, driven by the operand formats in vm/opcodes.h.
#include "vm/disasm.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "vm/lights.h"

namespace affray::vm {

namespace {
std::string FormatNumber(double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", x);
    return buf;
}

std::string SourceLine(const std::string& text, int line) {
    int current = 1;
    size_t begin = 0;
    while (current < line) {
        size_t nl = text.find('\n', begin);
        if (nl == std::string::npos) return {};
        begin = nl + 1;
        ++current;
    }
    size_t end = text.find('\n', begin);
    std::string s = text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    size_t first = s.find_first_not_of(" \t");
    return first == std::string::npos ? std::string() : s.substr(first);
}
}  // namespace

std::string DisassembleInstr(const Program& program, const Instr* in, size_t available) {
    if (static_cast<int>(in->op) >= kOpCount) return "<bad opcode " + std::to_string(int(in->op)) + ">";
    const OpInfo& info = Info(in->op);
    if (static_cast<size_t>(WordCount(info.format)) > available) return std::string(info.name) + " <operands missing>";
    std::string out = info.name;
    out.resize(std::max<size_t>(8, out.size() + 1), ' ');  // a name of 8 letters or more keeps a space
    bool first = true;
    for (int i = 0; info.format[i]; ++i) {
        char kind = info.format[i];
        if (kind == '-') continue;
        uint16_t x = OperandOf(in, i);
        out += first ? "" : ", ";
        first = false;
        if (kind == 'k') {
            out += "k" + std::to_string(x);
            if (x < program.constants.size()) out += " (" + FormatNumber(program.constants[x]) + ")";
        } else {
            out += "r" + std::to_string(x);
        }
    }
    if (OperationOf(in->op) == Operation::Texture)
        out += "  [texture " + std::to_string(in->flags) + "]";
    else if (in->op == Op::Light)
        out += in->flags == kAmbientSlot ? std::string("  [ambient]") : "  [light " + std::to_string(in->flags) + "]";
    else if (in->flags != 0)
        out += "  [channel " + std::to_string(in->flags) + "]";
    return out;
}

std::string Disassemble(const Program& program, const std::string& sourceText) {
    std::ostringstream out;
    out << "; shader " << program.shaderName << ": " << program.code.size() << " instructions, "
        << program.registerCount << " registers, " << program.constants.size() << " constants\n";
    out << "; globals read:";
    bool any = false;
    for (int g = 0; g < kGlobalCount; ++g) {
        uint16_t r = program.globalRegisters[g];
        if (r == kNoRegister) continue;
        any = true;
        int size = GlobalSize(static_cast<Global>(g));
        out << " " << GlobalName(static_cast<Global>(g)) << "=r" << r;
        if (size == 3) out << "..r" << r + 2;
    }
    out << (any ? "\n" : " none\n");
    for (const ProgramOutput& o : program.outputs) {
        out << "; output " << o.name << " =";
        for (int i = 0; i < o.size; ++i) out << " r" << o.registers[i];
        out << "\n";
    }
    if (program.textures)
        for (size_t i = 0; i < program.textures->size(); ++i) {
            const TextureSlot& slot = (*program.textures)[i];
            const texture::LookupOptions& o = slot.options;
            out << "; texture " << i << " = \"" << slot.path << "\" channel " << o.channel << ", wrap "
                << texture::WrapName(o.swrap) << " " << texture::WrapName(o.twrap) << ", filter "
                << texture::FilterName(o.filter) << ", blur " << FormatNumber(o.sblur) << " " << FormatNumber(o.tblur)
                << ", fill " << FormatNumber(o.fill) << (slot.map ? "" : " (no map: the fill)") << "\n";
        }
    int lastLine = -1;
    for (size_t pc = 0; pc < program.code.size(); ++pc) {
        int line = pc < program.lines.size() ? program.lines[pc] : 0;
        if (line != lastLine && line > 0) {
            out << "; " << line << ": " << SourceLine(sourceText, line) << "\n";
            lastLine = line;
        }
        char index[32];
        std::snprintf(index, sizeof index, "%4zu  ", pc);
        out << index << DisassembleInstr(program, &program.code[pc], program.code.size() - pc) << "\n";
        if (static_cast<int>(program.code[pc].op) < kOpCount) pc += WordCount(Info(program.code[pc].op).format) - 1;
    }
    return out.str();
}

std::string OpcodeTable() {
    std::string out =
        "| # | opcode | operands (A B C, Ext...) | operation | facts | RSL | meaning |\n"
        "|---|---|---|---|---|---|---|\n";
    for (int i = 0; i < kOpCount; ++i) {
        const Op op = static_cast<Op>(i);
        const OpInfo& info = Info(op);
        const Operation f = OperationOf(op);
        std::string facts;
        auto fact = [&](OperationFlag flag, const char* name) {
            if (!Has(f, flag)) return;
            if (!facts.empty()) facts += ", ";
            facts += name;
        };
        fact(kFoldable, "foldable");
        fact(kTruth, "truth value");
        fact(kCommutative, "commutative");
        fact(kSwapsExactly, "swaps exactly");
        fact(kDerivative, "derivative");
        fact(kJumps, "jumps");
        fact(kPointwiseSlope, "pointwise slope");
        std::string meaning = info.meaning;
        for (size_t at = meaning.find('|'); at != std::string::npos; at = meaning.find('|', at + 2))
            meaning.replace(at, 1, "\\|");
        out += "| " + std::to_string(i) + " | " + info.name + " | `" + info.format + "` | " +
               (f == Operation::None ? std::string("-") : Info(f).name) + " | " + facts + " | " +
               (f == Operation::None ? std::string() : "`" + std::string(Info(f).rsl) + "`") + " | " + meaning + " |\n";
    }
    return out;
}

}  // namespace affray::vm
