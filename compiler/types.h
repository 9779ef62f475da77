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

/// A global variable of surface and light shaders (RI Spec 3.2 table 15.1) and its type.
struct SurfaceGlobal {
    const char* name;
    Type type;
};
/// Those a surface shader has besides the VM's globals (vm/program.h), Cs and Os among them
/// (which are the VM's too, for surface shaders only).
inline constexpr SurfaceGlobal kSurfaceGlobals[] = {
    {"Cs", Type::Color},     {"Os", Type::Color},       {"Ci", Type::Color}, {"Oi", Type::Color},
    {"L", Type::Vector},     {"Cl", Type::Color},       {"Ol", Type::Color}, {"alpha", Type::Float},
    {"ncomps", Type::Float}, {"dPdtime", Type::Vector},
};

}  // namespace affray::compiler
