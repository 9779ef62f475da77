// compiler/types.h: the types of shading-language values as the compiler sees them.
#pragma once

#include "lang/ast.h"

namespace affray::compiler {

/// Bool is the type of comparisons and of && || !: a 1 or 0 in the VM, usable in conditions (and,
/// as in C, as a float).
enum class Type { Float, Point, Vector, Normal, Color, String, Void, Bool, Matrix };

const char* ToString(Type t);
Type FromTypeName(lang::TypeName t);

/// Point, vector, normal and color are triples: three scalars in the VM.
inline bool IsTriple(Type t) { return t == Type::Point || t == Type::Vector || t == Type::Normal || t == Type::Color; }
/// Point, vector and normal mix freely in arithmetic (RenderMan allows it); color does not mix
/// with them.
inline bool IsSpatial(Type t) { return t == Type::Point || t == Type::Vector || t == Type::Normal; }

inline int ScalarCount(Type t) {
    return IsTriple(t) ? 3 : t == Type::Matrix ? 16 : t == Type::Float || t == Type::Bool ? 1 : 0;
}
/// The types arithmetic works on.
inline bool IsNumeric(Type t) { return t == Type::Float || IsTriple(t) || t == Type::Matrix; }

}  // namespace affray::compiler
