// compiler/typecheck.cpp: the type rules (see typecheck.h).
// A rule takes the operand types as the lowering sees them: Bool is the type of a comparison,
// taken as the float 1 or 0 in arithmetic (as in C) but not as a triple's component.
#include "compiler/typecheck.h"

namespace affray::compiler {

using lang::AssignOp;
using lang::BinaryOp;

namespace {
Typed Ok(Type t) { return {t, {}}; }
Typed Error(std::string message) { return {Type::Void, std::move(message)}; }
Type Arithmetic(Type t) { return t == Type::Bool ? Type::Float : t; }
bool MixesColor(Type a, Type b) { return (a == Type::Color && IsSpatial(b)) || (b == Type::Color && IsSpatial(a)); }
bool MixesMatrix(Type a, Type b) { return (a == Type::Matrix && IsTriple(b)) || (b == Type::Matrix && IsTriple(a)); }

/// Comparisons and && ||: on the operands as written (a Bool is named "boolean").
Typed ComparisonType(BinaryOp op, Type a, Type b) {
    const std::string opName = lang::ToString(op);
    auto bad = [&](const std::string& why) {
        return Error("invalid operands to '" + opName + "' (" + ToString(a) + " and " + ToString(b) + ")" + why);
    };
    if (op == BinaryOp::And || op == BinaryOp::Or) {
        auto truth = [](Type t) { return t == Type::Bool || t == Type::Float; };
        if (!truth(a) || !truth(b)) return bad(": '" + opName + "' combines conditions");
        return Ok(Type::Bool);
    }
    // Strings compare by their ids (one id per distinct text).
    if (a == Type::String || b == Type::String) {
        if (a != b || (op != BinaryOp::Equal && op != BinaryOp::NotEqual))
            return bad(": strings compare only with == and != to strings");
        return Ok(Type::Bool);
    }
    const Type x = Arithmetic(a), y = Arithmetic(b);
    if (!IsNumeric(x) || !IsNumeric(y)) return bad("");
    if (op == BinaryOp::Equal || op == BinaryOp::NotEqual) {
        if (MixesColor(x, y)) return bad(": a color does not compare with a point, vector or normal");
        if (MixesMatrix(x, y)) return bad(": a matrix compares with a matrix or a float");
        return Ok(Type::Bool);  // triples and matrices: equal when every component is
    }
    if (x != Type::Float || y != Type::Float) return bad(": only floats are ordered");
    return Ok(Type::Bool);
}
}  // namespace

std::string Article(Type t) {
    std::string name = ToString(t);
    return (name[0] == 'a' || name[0] == 'e' || name[0] == 'i' || name[0] == 'o' || name[0] == 'u' ? "an " : "a ") +
           name;
}

Typed NegateType(Type a) {
    const Type x = Arithmetic(a);
    if (x != Type::Float && !IsTriple(x))
        return Error("invalid operand to unary '-' (" + std::string(ToString(x)) + ")");
    return Ok(x);
}

Typed BinaryType(BinaryOp op, Type a, Type b) {
    switch (op) {
        case BinaryOp::Less:
        case BinaryOp::LessEq:
        case BinaryOp::Greater:
        case BinaryOp::GreaterEq:
        case BinaryOp::Equal:
        case BinaryOp::NotEqual:
        case BinaryOp::And:
        case BinaryOp::Or: return ComparisonType(op, a, b);
        default: break;
    }
    // A boolean in arithmetic is the float 1 or 0, as in C.
    const Type x = Arithmetic(a), y = Arithmetic(b);
    auto bad = [&](const std::string& why) {
        return Error("invalid operands to '" + std::string(lang::ToString(op)) + "' (" + ToString(x) + " and " +
                     ToString(y) + ")" + why);
    };
    if (!IsNumeric(x) || !IsNumeric(y)) return bad("");
    if (x == Type::Matrix || y == Type::Matrix) {
        // Matrices multiply and divide (by the inverse) each other and floats; a point goes
        // through transform().
        const bool mulOrDiv = op == BinaryOp::Mul || op == BinaryOp::Div;
        if (!mulOrDiv || IsTriple(x) || IsTriple(y))
            return bad(": a matrix only multiplies or divides a matrix or a float (transform() applies it to a point)");
        return Ok(Type::Matrix);
    }
    switch (op) {
        case BinaryOp::Add:
        case BinaryOp::Sub:
        case BinaryOp::Mul:
        case BinaryOp::Div: {
            const bool mixesColor = MixesColor(x, y);
            if (mixesColor) return bad(": a color does not combine with a point, vector or normal");
            return Ok(IsTriple(x) ? x : y);  // a float with a triple: the triple's type
        }
        case BinaryOp::Dot:
            if (!IsTriple(x) || !IsTriple(y)) return bad(": '.' is the dot product of two triples");
            return Ok(Type::Float);
        case BinaryOp::Cross:
            if (!IsSpatial(x) || !IsSpatial(y)) return bad(": '^' is the cross product of two vectors");
            return Ok(Type::Vector);
        default: break;
    }
    return Error("invalid operands to '" + std::string(lang::ToString(op)) + "'");  // not reached: all ops above
}

Typed ConditionType(Type t) {
    // A float condition means "!= 0" (C's rule; some RenderMan compilers accept it too).
    if (t == Type::Bool || t == Type::Float) return Ok(Type::Bool);
    return Error("a condition must be a comparison or a float, not " + Article(t));
}

Typed TernaryType(Type x, Type y) {
    if (x == Type::Bool && y == Type::Bool) return Ok(Type::Bool);
    x = Arithmetic(x);
    y = Arithmetic(y);
    if (x == Type::String && y == Type::String) return Ok(Type::String);
    if (!IsNumeric(x) || !IsNumeric(y) || MixesColor(x, y) || MixesMatrix(x, y))
        return Error("the two results of '?:' have incompatible types (" + std::string(ToString(x)) + " and " +
                     ToString(y) + ")");
    return Ok(x == Type::Float ? y : x);  // a float arm is promoted to the other's type
}

Typed TripleComponentType(Type t) {
    // A comparison is not a component: (x > 0, 0, 0) is more likely a mistake than a mask.
    if (t != Type::Float) return Error("a triple's components must be floats, got " + Article(t));
    return Ok(Type::Float);
}

Typed MatrixEntryType(Type t) {
    if (Arithmetic(t) != Type::Float) return Error("a matrix's entries must be floats, got " + Article(t));
    return Ok(Type::Float);
}

Typed ConvertType(Type from, Type target, const std::string& what) {
    if (from == Type::Bool && target != Type::Bool) from = Type::Float;  // 1 or 0, as in C
    if (from == target) return Ok(target);
    if ((IsTriple(target) || target == Type::Matrix) && from == Type::Float) return Ok(target);
    if (IsSpatial(target) && IsSpatial(from)) return Ok(target);
    return Error("cannot assign " + Article(from) + " to " + what);
}

Typed CompoundAssignType(AssignOp op, Type var, Type value, const std::string& what) {
    value = Arithmetic(value);
    const bool matrixOp = var == Type::Matrix && (op == AssignOp::MulAssign || op == AssignOp::DivAssign);
    if ((!IsTriple(var) && var != Type::Float && !matrixOp) ||
        (var == Type::Matrix && value != Type::Float && value != Type::Matrix) ||
        (value == Type::Matrix && var != Type::Matrix))
        return Error("invalid operands to '" + std::string(lang::ToString(op)) + "' (" + ToString(var) + " and " +
                     ToString(value) + ")");
    if (IsTriple(value) && !IsTriple(var)) return Error("cannot assign " + Article(value) + " to " + what);
    if (MixesColor(var, value)) return Error("cannot assign " + Article(value) + " to " + what);
    return Ok(var);
}

Typed CastType(Type from, Type target, bool withSpace) {
    from = Arithmetic(from);
    // `color "hsv" (h, s, v)`, `point "shader" (x, y, z)`: components given in that space.
    if (withSpace && target == Type::Color && (from == Type::Float || IsTriple(from))) return Ok(target);
    if (withSpace && IsSpatial(target) && (from == Type::Float || IsSpatial(from))) return Ok(target);
    if (target == Type::Matrix && (from == Type::Float || from == Type::Matrix)) return Ok(target);
    if (from == target) return Ok(target);
    if (target == Type::Float || from == Type::String || target == Type::String || target == Type::Void ||
        target == Type::Matrix || from == Type::Matrix)
        return Error("cannot cast " + Article(from) + " to " + ToString(target));
    return Ok(target);
}

}  // namespace affray::compiler
