// compiler/spaces.h: the coordinate spaces a shader instance sees ("shader", "object", "world",
// "camera"), as matrices the compiler folds into the instance's program.
// "current" is the space the renderer computes P in (world space, in affray); every other named
// space maps to and from it. A space the map does not name is the identity (affray eval: every
// space is the identity).
#pragma once

#include <array>
#include <map>
#include <string>

namespace affray::compiler {

/// A 4x4 matrix, row-major, acting on column vectors (x, y, z, 1).
using Matrix4 = std::array<double, 16>;

inline constexpr Matrix4 kIdentity4 = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

struct SpaceTransform {
    Matrix4 toCurrent = kIdentity4;    // space -> current
    Matrix4 fromCurrent = kIdentity4;  // current -> space (the inverse)
};

using Spaces = std::map<std::string, SpaceTransform>;

}  // namespace affray::compiler
