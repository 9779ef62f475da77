// compiler/specialise.h: binding a program's parameters to one shader instance's values.
// The compiler emits *generic* programs, whose parameters are registers; each shader instance
// in a scene gets its own *specialised* copy, in which every parameter is a constant and the
// code is folded and pruned again (OSL's runtime optimiser is the model): whatever the
// instance's values make constant or dead disappears.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "vm/program.h"

namespace affray::compiler {

/// A value given to a shader parameter by the scene (or `affray eval --param`).
struct ParamOverride {
    ParamOverride() = default;
    ParamOverride(std::string name_, std::vector<double> numbers_)
        : name(std::move(name_)), numbers(std::move(numbers_)) {}
    /// A string parameter's value.
    static ParamOverride String(std::string name, std::string text) {
        ParamOverride o;
        o.name = std::move(name);
        o.text = std::move(text);
        return o;
    }

    std::string name;
    std::vector<double> numbers;      // 1 for a float, 3 (or 1, spread) for a triple
    std::optional<std::string> text;  // a string parameter's value (then `numbers` is empty)
};

/// A global that is the same everywhere on a surface (N of a flat patch, E, du...): the
/// renderer knows it per primitive, so the program can fold it like a constant.
struct ConstantGlobal {
    vm::Global global;
    std::array<double, 3> value{};  // value[0] only, for a float global
};

/// The value of every parameter of `program`: its override, else its default. Problems with the
/// overrides are appended to *errors as sentences, and the result is empty.
std::optional<std::vector<std::vector<double>>> BindParameters(const vm::Program& program,
                                                               const std::vector<ParamOverride>& overrides,
                                                               std::vector<std::string>* errors);

/// `program` with every parameter bound to its override, else its default, and every global in
/// `constantGlobals` bound to its value, then folded, shared and pruned again. Problems with the
/// overrides (unknown name, wrong count, NaN or infinity) are appended to *errors as sentences,
/// and the result is empty.
std::optional<vm::Program> Specialise(const vm::Program& program, const std::vector<ParamOverride>& overrides,
                                      std::vector<std::string>* errors,
                                      const std::vector<ConstantGlobal>& constantGlobals = {});

}  // namespace affray::compiler
