// compiler/types.cpp: names of types.
#include "compiler/types.h"

namespace affray::compiler {

const char* ToString(Type t) {
    switch (t) {
        case Type::Float: return "float";
        case Type::Point: return "point";
        case Type::Vector: return "vector";
        case Type::Normal: return "normal";
        case Type::Color: return "color";
        case Type::String: return "string";
        case Type::Void: return "void";
        case Type::Bool: return "boolean";
        case Type::Matrix: return "matrix";
    }
    return "?";
}

Type FromTypeName(lang::TypeName t) {
    switch (t) {
        case lang::TypeName::Float: return Type::Float;
        case lang::TypeName::Point: return Type::Point;
        case lang::TypeName::Vector: return Type::Vector;
        case lang::TypeName::Normal: return Type::Normal;
        case lang::TypeName::Color: return Type::Color;
        case lang::TypeName::String: return Type::String;
        case lang::TypeName::Void: return Type::Void;
        case lang::TypeName::Matrix: return Type::Matrix;
    }
    return Type::Void;
}

}  // namespace affray::compiler
