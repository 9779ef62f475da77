// compiler/builtins.cpp: the table of built-in functions and how each lowers.
// A VM operation whose RSL spelling in the opcode table (vm/opcodes.h) is a call of its operands,
// "name(x)" or "name(y, x)", is the built-in of that name on floats, with no row here (sin,
// atan(y, x), ...): adding such an operation to the table adds the built-in. For anything else
// (other argument types, a lowering to several operations) add a row to kRows with its argument
// pattern and a lowering lambda; a row takes the place of the table's built-in of the same name
// and argument count.
// Pattern letters: 'f' float, 't' point/vector/normal (a float is promoted), 'c' color,
// 'a' float or any triple (the result has the widest argument type), 'm' matrix (a float is
// promoted: x times the identity).
#include "compiler/builtins.h"

#include <cctype>
#include <cmath>
#include <functional>
#include <numbers>
#include <string_view>

namespace affray::compiler {

namespace {

using Lowering = std::function<Value(ValueOps&, const std::vector<Value>&)>;

struct Builtin {
    std::string_view name;
    const char* pattern;
    Lowering lower;
};

Value Scalar(ValueOps& ops, IrOp op, const Value& x) { return ops.Map(op, x); }

/// The operand count of an RSL spelling that calls its operands, "name(x)" or "name(y, x)" (a
/// letter each), and its name; 0 for any other spelling ("x + y", "c ? x : y").
int CallOperands(std::string_view rsl, std::string_view* name) {
    const size_t open = rsl.find('(');
    if (open == 0 || open == std::string_view::npos) return 0;
    for (size_t i = 0; i < open; ++i)
        if (!std::isalnum(static_cast<unsigned char>(rsl[i]))) return 0;
    *name = rsl.substr(0, open);
    // Then a letter and ", " or ")", as many times as there are operands.
    for (size_t i = open + 1, count = 1; i + 1 < rsl.size(); i += 3, ++count) {
        if (!std::islower(static_cast<unsigned char>(rsl[i]))) return 0;
        if (rsl.substr(i + 1) == ")") return static_cast<int>(count);
        if (rsl.substr(i + 1, 2) != ", ") return 0;
    }
    return 0;
}

Value Mix(ValueOps& o, const std::vector<Value>& a) {
    // mix(x, y, t) = x*(1-t) + y*t (per component for a triple t)
    Value oneMinusT = o.Sub(o.Constant(1.0), a[2]);
    return o.Add(o.Mul(a[0], oneMinusT), o.Mul(a[1], a[2]));
}

const std::vector<Builtin>& Rows() {
    using A = const std::vector<Value>&;
    static const std::vector<Builtin> kRows = {
        {"log", "ff", [](ValueOps& o, A a) { return o.Div(Scalar(o, IrOp::Log, a[0]), Scalar(o, IrOp::Log, a[1])); }},
        {"inversesqrt", "f", [](ValueOps& o, A a) { return o.Div(o.Constant(1.0), Scalar(o, IrOp::Sqrt, a[0])); }},
        {"pow", "ff", [](ValueOps& o, A a) { return o.Pow(a[0], a[1]); }},
        {"radians", "f", [](ValueOps& o, A a) { return o.Mul(a[0], o.Constant(std::numbers::pi / 180)); }},
        {"degrees", "f", [](ValueOps& o, A a) { return o.Mul(a[0], o.Constant(180 / std::numbers::pi)); }},
        {"length", "t", [](ValueOps& o, A a) { return o.Length(a[0]); }},
        {"distance", "tt", [](ValueOps& o, A a) { return o.Distance(a[0], a[1]); }},
        {"normalize", "t", [](ValueOps& o, A a) { return o.Promote(o.Normalize(a[0]), Type::Vector); }},
        {"xcomp", "t", [](ValueOps& o, A a) { return o.Component(a[0], 0); }},
        {"ycomp", "t", [](ValueOps& o, A a) { return o.Component(a[0], 1); }},
        {"zcomp", "t", [](ValueOps& o, A a) { return o.Component(a[0], 2); }},
        {"Du", "a", [](ValueOps& o, A a) { return Scalar(o, IrOp::DerivU, a[0]); }},
        {"Dv", "a", [](ValueOps& o, A a) { return Scalar(o, IrOp::DerivV, a[0]); }},
        {"reflect", "tt",
         [](ValueOps& o, A a) {
             // reflect(I, N) = I - 2 (I.N) N
             return o.Promote(o.Sub(a[0], o.Mul(o.Mul(o.Constant(2.0), o.Dot(a[0], a[1])), a[1])), Type::Vector);
         }},
        {"area", "t",
         [](ValueOps& o, A a) {
             // area(P) = length(Du(P)*du ^ Dv(P)*dv)
             Value du = o.Float(o.ir().Global(vm::Global::du, 0)), dv = o.Float(o.ir().Global(vm::Global::dv, 0));
             Value sideU = o.Mul(Scalar(o, IrOp::DerivU, a[0]), du), sideV = o.Mul(Scalar(o, IrOp::DerivV, a[0]), dv);
             return o.Length(o.Cross(sideU, sideV));
         }},
        {"filterwidth", "f",
         [](ValueOps& o, A a) {
             // prman's filterwidth(x) (as Gritz's filterwidth.h defines it): how much x changes
             // across one step of the parameters, abs(Du(x) du) + abs(Dv(x) dv), at least 1e-6.
             Value du = o.Float(o.ir().Global(vm::Global::du, 0)), dv = o.Float(o.ir().Global(vm::Global::dv, 0));
             Value change = o.Add(o.Map(IrOp::Abs, o.Mul(Scalar(o, IrOp::DerivU, a[0]), du)),
                                  o.Map(IrOp::Abs, o.Mul(Scalar(o, IrOp::DerivV, a[0]), dv)));
             return o.Binary(IrOp::Max, change, o.Constant(1e-6));
         }},
        {"filterwidthp", "t",
         [](ValueOps& o, A a) {
             // filterwidthp(p) = sqrt(area(p)), at least 1e-6.
             Value du = o.Float(o.ir().Global(vm::Global::du, 0)), dv = o.Float(o.ir().Global(vm::Global::dv, 0));
             Value sideU = o.Mul(Scalar(o, IrOp::DerivU, a[0]), du), sideV = o.Mul(Scalar(o, IrOp::DerivV, a[0]), dv);
             return o.Binary(IrOp::Max, Scalar(o, IrOp::Sqrt, o.Length(o.Cross(sideU, sideV))), o.Constant(1e-6));
         }},
        {"Deriv", "af",
         [](ValueOps& o, A a) {
             // Deriv(num, den) = Du(num)/Du(den) + Dv(num)/Dv(den), a term 0 where den does not
             // change in that direction (Deriv(f(u), u) is f'(u), not NaN from Dv's 0/0).
             auto term = [&](IrOp d) {
                 const Value den = Scalar(o, d, a[1]);
                 return o.SelectValue(o.Binary(IrOp::Eq, den, o.Constant(0.0)), o.Constant(0.0),
                                      o.Div(Scalar(o, d, a[0]), den));
             };
             return o.Add(term(IrOp::DerivU), term(IrOp::DerivV));
         }},
        {"calculatenormal", "t",
         [](ValueOps& o, A a) {
             // RenderMan: calculatenormal(P) = Du(P) ^ Dv(P)
             Value du = Scalar(o, IrOp::DerivU, a[0]), dv = Scalar(o, IrOp::DerivV, a[0]);
             return o.Promote(o.Cross(du, dv), Type::Normal);
         }},
        {"floor", "a", [](ValueOps& o, A a) { return Scalar(o, IrOp::Floor, a[0]); }},
        {"ceil", "a", [](ValueOps& o, A a) { return Scalar(o, IrOp::Ceil, a[0]); }},
        {"round", "a", [](ValueOps& o, A a) { return Scalar(o, IrOp::Round, a[0]); }},
        {"mod", "aa",
         [](ValueOps& o, A a) {
             // RenderMan's mod has the sign of the divisor: a - b*floor(a/b)
             return o.Sub(a[0], o.Mul(a[1], o.Map(IrOp::Floor, o.Div(a[0], a[1]))));
         }},
        {"min", "aa", [](ValueOps& o, A a) { return o.Binary(IrOp::Min, a[0], a[1]); }},
        {"min", "aaa", [](ValueOps& o, A a) { return o.Binary(IrOp::Min, o.Binary(IrOp::Min, a[0], a[1]), a[2]); }},
        {"max", "aa", [](ValueOps& o, A a) { return o.Binary(IrOp::Max, a[0], a[1]); }},
        {"max", "aaa", [](ValueOps& o, A a) { return o.Binary(IrOp::Max, o.Binary(IrOp::Max, a[0], a[1]), a[2]); }},
        {"clamp", "aaa", [](ValueOps& o, A a) { return o.Clamp(a[0], a[1], a[2]); }},
        {"step", "ff",
         [](ValueOps& o, A a) {
             // step(edge, x) = x < edge ? 0 : 1, i.e. edge <= x
             return o.Binary(IrOp::Le, a[0], a[1]);
         }},
        {"smoothstep", "fff",
         [](ValueOps& o, A a) {
             // 0 below e0, 1 above e1, the cubic Hermite 3t^2 - 2t^3 between. t is in [0, 1] even
             // where e0 == e1 (fmin/fmax drop the NaN of 0/0), and so is the cubic, rounding
             // included: the outer clamp changes no value, it tells the bounds (issue 12).
             Value t = o.Clamp(o.Div(o.Sub(a[2], a[0]), o.Sub(a[1], a[0])), o.Constant(0.0), o.Constant(1.0));
             Value h = o.Mul(o.Map(IrOp::Sqr, t), o.Sub(o.Constant(3.0), o.Mul(o.Constant(2.0), t)));
             return o.Clamp(h, o.Constant(0.0), o.Constant(1.0));
         }},
        {"faceforward", "tt",
         [](ValueOps& o, A a) {
             // faceforward(N, I) = I.Ng > 0 ? -N : N
             Value ng = o.Triple(Type::Normal, o.ir().Global(vm::Global::Ng, 0), o.ir().Global(vm::Global::Ng, 1),
                                 o.ir().Global(vm::Global::Ng, 2));
             return o.Promote(o.SelectValue(o.Binary(IrOp::Lt, o.Constant(0.0), o.Dot(a[1], ng)), o.Neg(a[0]), a[0]),
                              Type::Vector);
         }},
        {"faceforward", "ttt",
         [](ValueOps& o, A a) {
             // faceforward(N, I, Nref) = I.Nref > 0 ? -N : N
             return o.Promote(o.SelectValue(o.Binary(IrOp::Lt, o.Constant(0.0), o.Dot(a[1], a[2])), o.Neg(a[0]), a[0]),
                              Type::Vector);
         }},
        {"determinant", "m", [](ValueOps& o, A a) { return o.Float(o.Determinant(a[0])); }},
        {"translate", "mt", [](ValueOps& o, A a) { return o.Translate(a[0], a[1]); }},
        {"rotate", "mft", [](ValueOps& o, A a) { return o.Rotate(a[0], a[1], a[2]); }},
        {"scale", "mt", [](ValueOps& o, A a) { return o.Scale(a[0], a[1]); }},
        {"rotate", "tftt",
         [](ValueOps& o, A a) {
             // rotate(Q, angle, P0, P1): Q turned by angle about the line through P0 and P1 (move
             // P0 to the origin, rotate about P1 - P0, move back).
             const Value toLine = o.Translate(o.Promote(o.Constant(1.0), Type::Matrix), a[2]);
             const Value turn = o.Rotate(toLine, a[1], o.Sub(a[3], a[2]));
             const Value m = o.Translate(turn, o.Neg(a[2]));
             return o.Promote(o.TransformBy(m, a[0], Type::Point), a[0].type);
         }},
        {"mix", "aaf", Mix},
        // A color (or point, vector, normal) t mixes component by component (RSL 3.2, prman); the
        // result has x and y's type (t's only when x and y are floats).
        {"mix", "aac", Mix},
        {"mix", "aat", Mix},
    };
    return kRows;
}

/// The table's built-ins that no row takes the place of (see the head comment), in the table's
/// order, then the rows.
const std::vector<Builtin>& Table() {
    static const std::vector<Builtin> kBuiltins = [] {
        using A = const std::vector<Value>&;
        std::vector<Builtin> all;
        for (int i = 1; i < vm::kOperationCount; ++i) {
            const vm::Operation f = static_cast<vm::Operation>(i);
            std::string_view name;
            const int n = CallOperands(vm::Info(f).rsl, &name);
            if (n < 1 || n > 2 || n != vm::Info(f).operands) continue;
            bool replaced = false;
            for (const Builtin& row : Rows())
                replaced |= row.name == name && std::char_traits<char>::length(row.pattern) == static_cast<size_t>(n);
            if (replaced) continue;
            const IrOp op = IrOpOf(f);
            if (n == 1)
                all.push_back({name, "f", [op](ValueOps& o, A a) { return Scalar(o, op, a[0]); }});
            else
                all.push_back({name, "ff", [op](ValueOps& o, A a) { return o.Binary(op, a[0], a[1]); }});
        }
        all.insert(all.end(), Rows().begin(), Rows().end());
        return all;
    }();
    return kBuiltins;
}

bool ArgMatches(char pattern, Type type) {
    switch (pattern) {
        case 'f': return type == Type::Float;
        case 't': return IsSpatial(type) || type == Type::Float;
        case 'c': return type == Type::Color || type == Type::Float;
        case 'a': return type == Type::Float || IsTriple(type);
        case 'm': return type == Type::Matrix || type == Type::Float;
    }
    return false;
}

std::string DescribePattern(const char* pattern) {
    std::string out = "(";
    for (const char* p = pattern; *p; ++p) {
        if (p != pattern) out += ", ";
        out += *p == 'f'   ? "float"
               : *p == 't' ? "point"
               : *p == 'c' ? "color"
               : *p == 'm' ? "matrix"
                           : "float or triple";
    }
    return out + ")";
}

}  // namespace

std::vector<std::string> TableBuiltinNames() {
    std::vector<std::string> names;
    for (const Builtin& b : Table()) names.emplace_back(b.name);
    return names;
}

std::optional<Value> LowerBuiltin(ValueOps& ops, const lang::Expr& call, const std::vector<Value>& args,
                                  lang::Diagnostics& diags) {
    std::vector<const Builtin*> candidates;
    for (const Builtin& b : Table())
        if (call.name == b.name) candidates.push_back(&b);
    if (candidates.empty()) {
        diags.error(call.loc, "unknown function '" + call.name + "'");
        return std::nullopt;
    }

    for (const Builtin* b : candidates) {
        if (std::char_traits<char>::length(b->pattern) != args.size()) continue;
        bool ok = true;
        Type widest = Type::Float;
        for (size_t i = 0; i < args.size() && ok; ++i) {
            ok = ArgMatches(b->pattern[i], args[i].type);
            // Only the 'a' arguments decide the type they share (mix's color t does not).
            if (b->pattern[i] == 'a' && IsTriple(args[i].type)) widest = args[i].type;
        }
        if (!ok) continue;
        // Promote float arguments where the pattern wants a triple.
        std::vector<Value> promoted = args;
        for (size_t i = 0; i < args.size(); ++i) {
            char p = b->pattern[i];
            if (p == 't' && args[i].type == Type::Float) promoted[i] = ops.Promote(args[i], Type::Point);
            if (p == 'c' && args[i].type == Type::Float) promoted[i] = ops.Promote(args[i], Type::Color);
            if (p == 'a' && IsTriple(widest)) promoted[i] = ops.Promote(args[i], widest);
            if (p == 'm') promoted[i] = ops.Promote(args[i], Type::Matrix);
        }
        return b->lower(ops, promoted);
    }

    // No overload matched: say what was expected.
    const Builtin* first = candidates.front();
    if (candidates.size() == 1 && std::char_traits<char>::length(first->pattern) != args.size()) {
        size_t n = std::char_traits<char>::length(first->pattern);
        diags.error(call.loc, "'" + call.name + "' expects " + std::to_string(n) + " argument" + (n == 1 ? "" : "s") +
                                  ", got " + std::to_string(args.size()));
        return std::nullopt;
    }
    std::string got = "(";
    for (size_t i = 0; i < args.size(); ++i) got += (i ? ", " : "") + std::string(ToString(args[i].type));
    got += ")";
    std::string expected;
    for (const Builtin* b : candidates) expected += (expected.empty() ? "" : " or ") + DescribePattern(b->pattern);
    diags.error(call.loc, "no version of '" + call.name + "' takes " + got + "; expected " + expected);
    return std::nullopt;
}

}  // namespace affray::compiler
