// vm/program.h: a compiled shader program, the unit the interpreter runs and files store.
// A program is straight-line register code over scalars: the caller writes the globals the
// program reads into their registers, runs it, and reads the outputs' registers.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "texture/texture.h"
#include "vm/opcodes.h"

namespace affray::vm {

/// The shader globals a program can read (RenderMan names). `time` and `dtime` are the shutter's
/// opening time and its length: a displacement is evaluated once for all the times of the
/// shutter, at its opening, as a Reyes renderer shades its grids (renderer/prepare.cpp binds both
/// as constants of each program). Cs and Os, the surface's colour and opacity, are globals of
/// surface shaders only (a displacement shader cannot name them), Ps (the point being lit) of
/// light shaders only.
#define AFFRAY_GLOBALS(X) \
    X(P, 3)               \
    X(N, 3)               \
    X(Ng, 3)              \
    X(I, 3)               \
    X(E, 3)               \
    X(dPdu, 3)            \
    X(dPdv, 3)            \
    X(s, 1)               \
    X(t, 1)               \
    X(u, 1)               \
    X(v, 1)               \
    X(du, 1)              \
    X(dv, 1)              \
    X(time, 1)            \
    X(dtime, 1)           \
    X(Cs, 3)              \
    X(Os, 3)              \
    X(Ps, 3)

enum class Global : uint8_t {
#define AFFRAY_GLOBAL_ENUM(name, size) name,
    AFFRAY_GLOBALS(AFFRAY_GLOBAL_ENUM)
#undef AFFRAY_GLOBAL_ENUM
};
#define AFFRAY_GLOBAL_COUNT(name, size) +1
inline constexpr int kGlobalCount = 0 AFFRAY_GLOBALS(AFFRAY_GLOBAL_COUNT);
#undef AFFRAY_GLOBAL_COUNT

const char* GlobalName(Global g);
int GlobalSize(Global g);  // 1 for floats, 3 for triples

inline constexpr uint16_t kNoRegister = 0xffff;

/// A named result of the program: "P" or "N", one or three registers.
struct ProgramOutput {
    std::string name;
    int size = 3;
    std::array<uint16_t, 3> registers{kNoRegister, kNoRegister, kNoRegister};
};

/// A shader parameter the program reads from registers (a program not yet specialised): the
/// caller's value, or the default, is written there before each run.
struct ProgramParam {
    std::string name;
    std::string type;  // "float", "point", "vector", "normal", "color", "matrix"; "float[4]"...
    int size = 1;      // registers: 1, 3 or 16 per element
    uint16_t firstRegister = kNoRegister;
    std::vector<double> defaults;  // size values
};

/// What one texture lookup of a program reads: the file, the options of its call site (the
/// channel included: a color lookup takes three slots, one per channel), and the map, read when
/// the program was made (compiled or loaded). A slot without a map (the file was missing and the
/// call gave a "fill") gives the fill value.
struct TextureSlot {
    std::string path;
    texture::LookupOptions options;
    /// The call gave a "fill": a file that cannot be read is then a warning, not an error.
    bool fillIfMissing = false;
    /// The parameters whose defaults gave these options (a generic program's: the options of an
    /// instance are its own); specialising the program with another value of one is refused.
    std::vector<std::string> dependsOn;
    std::shared_ptr<const texture::TextureMap> map;
};
using TextureSlots = std::vector<TextureSlot>;
inline constexpr int kMaxTextureSlots = 256;  // the flags byte of Texture2 and Texture8

struct Program {
    std::string shaderName;
    std::string sourcePath;
    std::vector<Instr> code;
    std::vector<int> lines;  // source line of each instruction (debug line table), 0 if none
    std::vector<double> constants;
    int registerCount = 0;
    /// Base register of each global the program reads (three consecutive for triples), or
    /// kNoRegister: the renderer computes only the globals that are read.
    std::array<uint16_t, kGlobalCount> globalRegisters;
    std::vector<ProgramOutput> outputs;
    /// Parameters still read from registers; empty once the program is specialised (every
    /// parameter then is a constant folded into the code).
    std::vector<ProgramParam> params;
    /// Coordinate spaces the shader names (other than "current"). A generic program computes
    /// them as the identity; an instance compiled from source has their matrices folded in.
    std::vector<std::string> spaces;
    /// The texture lookups' slots (Texture2 and Texture8 name theirs in the flags byte): shared,
    /// never changed once made, by the programs of one compilation and the pruned programs made
    /// from them. Null if the program reads no texture.
    std::shared_ptr<const TextureSlots> textures;

    Program() { globalRegisters.fill(kNoRegister); }

    bool readsGlobal(Global g) const { return globalRegisters[static_cast<int>(g)] != kNoRegister; }
    /// The output called `name`, or nullptr.
    const ProgramOutput* findOutput(const std::string& name) const;
    /// True if the program takes derivatives (Du, Dv, calculatenormal): it then needs a number
    /// type with derivatives (Dual) to give meaningful results.
    bool usesDerivatives() const;
};

}  // namespace affray::vm

namespace affray::vm {
/// The program of a surface without displacement: outputs P and N are the globals P and N.
Program IdentityProgram();
}  // namespace affray::vm
