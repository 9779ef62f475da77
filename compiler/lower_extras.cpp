// compiler/lower_extras.cpp: the rest of RenderMan's library that needs the lowerer (RI Spec
// 3.2, chapter 15): strings (format, concat, match), printf, ctransform, fresnel (output
// arguments), refract, ptlined and random. Each is composed of IR operations, so every number
// type bounds it with the rules of those operations.
// Strings are compile-time constants (Lowerer::StringValue); a string built from a value that
// varies is a "varying string", usable only where no constant is needed (printf, ==).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "compiler/builtins.h"
#include "compiler/builtins_color.h"
#include "compiler/lowerer.h"
#include "compiler/regex_match.h"

namespace affray::compiler {

namespace {

constexpr const char* kExtraCalls[] = {"printf",  "format",  "concat",  "match", "ctransform",
                                       "fresnel", "refract", "ptlined", "random"};

/// printf's and format's rendering of a constant value: %f %g %e %d %i %s %p %c %m %%, with
/// flags, width and precision passed to snprintf for each float.
std::string FormatText(const std::string& format, const std::vector<std::vector<double>>& numbers,
                       const std::vector<std::string>& strings, const std::vector<Type>& types) {
    std::string out;
    size_t next = 0;
    for (size_t i = 0; i < format.size(); ++i) {
        if (format[i] != '%') {
            out += format[i];
            continue;
        }
        size_t j = i + 1;
        while (j < format.size() && std::strchr("-+ #0123456789.", format[j])) ++j;
        if (j >= format.size()) break;
        const char conv = format[j];
        if (conv == '%') {
            out += '%';
            i = j;
            continue;
        }
        std::string spec = format.substr(i, j - i);
        const char floatConv = conv == 'd' || conv == 'i' ? 'd' : conv == 'e' || conv == 'g' ? conv : 'f';
        if (next < types.size()) {
            if (types[next] == Type::String) {
                out += strings[next];
            } else {
                const std::vector<double>& v = numbers[next];
                for (size_t k = 0; k < v.size(); ++k) {
                    char buf[128];
                    if (floatConv == 'd')
                        std::snprintf(buf, sizeof buf, (spec + "lld").c_str(), static_cast<long long>(v[k]));
                    else
                        std::snprintf(buf, sizeof buf, (spec + floatConv).c_str(), v[k]);
                    out += (k ? " " : "") + std::string(buf);
                }
            }
        }
        ++next;
        i = j;
    }
    return out;
}

/// refract(I, N, eta) = eta I - (eta I.N + sqrt(k)) N with k = 1 - eta^2 (1 - (I.N)^2), or
/// (0, 0, 0) where k < 0 (total internal reflection; the root of max(k, 0) keeps the other arm
/// finite for the bound types). RI Spec 3.2, section 15.2.
Value Refract(ValueOps& o, const Value& i, const Value& n, const Value& eta) {
    const Value one = o.Constant(1.0), zero = o.Constant(0.0);
    const Value iDotN = o.Dot(i, n);
    const Value k = o.Sub(one, o.Mul(o.Mul(eta, eta), o.Sub(one, o.Mul(iDotN, iDotN))));
    const Value root = o.Map(IrOp::Sqrt, o.Binary(IrOp::Max, k, zero));
    const Value t = o.Sub(o.Mul(eta, i), o.Mul(o.Add(o.Mul(eta, iDotN), root), n));
    return o.SelectValue(o.Binary(IrOp::Lt, k, zero), o.Promote(zero, Type::Vector), o.Promote(t, Type::Vector));
}

}  // namespace

bool Lowerer::IsExtraCall(const std::string& name) {
    for (const char* n : kExtraCalls)
        if (name == n) return true;
    return false;
}

std::vector<std::string> ExtraCallNames() { return {std::begin(kExtraCalls), std::end(kExtraCalls)}; }

std::vector<std::string> KnownBuiltinNames() {
    std::vector<std::string> names = TableBuiltinNames();
    for (const char* n : {"noise", "pnoise", "cellnoise", "transform", "vtransform", "ntransform", "spline",
                          "filterstep", "depth", "comp", "setcomp", "setxcomp", "setycomp", "setzcomp"})
        names.emplace_back(n);
    for (const std::vector<std::string>& more : {ExtraCallNames(), SurfaceCallNames()})
        names.insert(names.end(), more.begin(), more.end());
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    return names;
}

Value Lowerer::VaryingString() {
    // Negative ids name no constant: StringOf gives nothing, so a use that needs the text
    // reports that it must be known when the shader is compiled.
    const ValueId id = ir().Const(-1.0 - m_varyingStrings++);
    return {Type::String, {id, id, id}};
}

std::optional<Value> Lowerer::LowerExtraCall(const lang::Expr& e, Type expected) {
    const std::string& name = e.name;
    // fresnel's last arguments are outputs: variables, lowered below.
    const size_t inputs = name == "fresnel" ? std::min<size_t>(e.args.size(), 3) : e.args.size();
    std::vector<Value> args;
    bool ok = true;
    for (size_t i = 0; i < inputs; ++i) {
        std::optional<Value> v = LowerExpr(*e.args[i]);
        if (v && v->type == Type::Bool) v->type = Type::Float;
        if (v) args.push_back(*v);
        ok = ok && v.has_value();
    }
    if (!ok) return std::nullopt;
    m_ops.SetLine(e.loc.line);
    auto bad = [&](const std::string& expects) {
        std::string got;
        for (const Value& a : args) got += (got.empty() ? "" : ", ") + std::string(ToString(a.type));
        m_diags.error(e.loc, "no version of '" + name + "' takes (" + got + "); expected " + expects);
        return std::nullopt;
    };
    auto isVector = [](const Value& v) { return IsSpatial(v.type) || v.type == Type::Float; };

    if (name == "printf" || name == "format" || name == "concat") {
        const bool isConcat = name == "concat";
        if (args.empty() ||
            (isConcat &&
             std::any_of(args.begin(), args.end(), [](const Value& a) { return a.type != Type::String; })) ||
            args[0].type != Type::String)
            return bad(isConcat ? "strings" : "(string format, ...)");
        // printf prints nothing in affray (a shader's messages have no place in a bound); its
        // arguments are still checked.
        if (name == "printf") return Value{Type::Void, {}};
        std::vector<std::vector<double>> numbers;
        std::vector<std::string> strings;
        std::vector<Type> types;
        for (const Value& a : args) {
            types.push_back(a.type);
            strings.emplace_back();
            numbers.emplace_back();
            if (a.type == Type::String) {
                std::optional<std::string> text = StringOf(a);
                if (!text || Unknown(*text)) return VaryingString();
                strings.back() = *text;
                continue;
            }
            for (int c = 0; c < a.size(); ++c) {
                std::optional<double> k = ir().ConstValue(a.c[c]);
                if (!k) return VaryingString();
                numbers.back().push_back(*k);
            }
        }
        if (isConcat) {
            std::string all;
            for (const std::string& s : strings) all += s;
            return StringValue(all);
        }
        types.erase(types.begin());
        strings.erase(strings.begin());
        numbers.erase(numbers.begin());
        return StringValue(FormatText(*StringOf(args[0]), numbers, strings, types));
    }

    if (name == "match") {
        // match(pattern, subject): 1 where the regular expression matches part of the subject.
        if (args.size() != 2 || args[0].type != Type::String || args[1].type != Type::String)
            return bad("(string pattern, string subject)");
        std::optional<std::string> pattern = StringOf(args[0]), subject = StringOf(args[1]);
        if (!pattern || !subject) {
            m_diags.error(e.loc, "the strings 'match' compares must be known when the shader is compiled");
            return std::nullopt;
        }
        if (Unknown(*pattern) || Unknown(*subject)) return m_ops.Constant(0.0);
        std::string error;
        const std::optional<bool> found = RegexSearch(*pattern, *subject, &error);
        if (!found) {
            m_diags.error(e.args[0]->loc, error);
            return std::nullopt;
        }
        return m_ops.Constant(*found ? 1.0 : 0.0);
    }

    if (name == "ctransform") {
        // ctransform([from,] to, c): c from `from` (else rgb) to rgb, then to `to`.
        if ((args.size() != 2 && args.size() != 3) ||
            (args.back().type != Type::Color && args.back().type != Type::Float))
            return bad("([string from,] string to, color c)");
        std::vector<std::string> spaces;
        for (size_t i = 0; i + 1 < args.size(); ++i) {
            std::optional<std::string> space = StringOf(args[i]);
            if (!space || args[i].type != Type::String) {
                m_diags.error(e.args[i]->loc, "the color space must be a string known when the shader is compiled");
                return std::nullopt;
            }
            if (Unknown(*space)) space = "rgb";
            if (!IsColorSpace(*space)) {
                m_diags.error(e.args[i]->loc,
                              "unknown color space '" + *space + "' (rgb, hsv, hsl, xyz, XYZ, xyY and YIQ are known)");
                return std::nullopt;
            }
            spaces.push_back(*space);
        }
        const std::string from = spaces.size() == 2 ? spaces[0] : "rgb";
        return RgbToColor(m_ops, spaces.back(), ColorToRgb(m_ops, from, args.back()));
    }

    if (name == "refract") {
        if (args.size() != 3 || !isVector(args[0]) || !isVector(args[1]) || args[2].type != Type::Float)
            return bad("(vector I, normal N, float eta)");
        return Refract(m_ops, m_ops.Promote(args[0], Type::Vector), m_ops.Promote(args[1], Type::Vector), args[2]);
    }

    if (name == "ptlined") {
        // ptlined(P0, P1, Q): the distance from Q to the segment P0 P1 (to its nearer end
        // beyond the ends; |Q - P0| when the ends coincide).
        if (args.size() != 3 || !isVector(args[0]) || !isVector(args[1]) || !isVector(args[2]))
            return bad("(point P0, point P1, point Q)");
        const Value p0 = m_ops.Promote(args[0], Type::Point), d = m_ops.Sub(m_ops.Promote(args[1], Type::Point), p0);
        const Value q = m_ops.Sub(m_ops.Promote(args[2], Type::Point), p0);
        const Value dd = m_ops.Dot(d, d);
        const Value zero = m_ops.Constant(0.0);
        const Value t = m_ops.SelectValue(m_ops.Binary(IrOp::Eq, dd, zero), zero,
                                          m_ops.Clamp(m_ops.Div(m_ops.Dot(q, d), dd), zero, m_ops.Constant(1.0)));
        return m_ops.Length(m_ops.Sub(q, m_ops.Mul(t, d)));
    }

    if (name == "random") {
        // random(): a float, or a color or point as the context wants, in [0, 1). Deterministic
        // (renders must not depend on threads or order): cellnoise of (u, v) on a 2^20 grid,
        // each call site and channel on cells of its own.
        if (!args.empty()) return bad("()");
        const ValueId u = ir().Global(vm::Global::u, 0), v = ir().Global(vm::Global::v, 0);
        const ValueId scale = ir().Const(1048576.0);
        const int site = m_randomCalls++;
        const Type result = IsTriple(expected) ? expected : Type::Float;
        Value out{result, {}};
        for (int c = 0; c < 3; ++c) {
            if (c > 0 && result == Type::Float) {
                out.c[c] = out.c[0];
                continue;
            }
            const ValueId w = ir().Const(static_cast<double>(3 * site + c));
            const std::vector<ValueId> at = {ir().Binary(IrOp::Mul, u, scale, Line()),
                                             ir().Binary(IrOp::Mul, v, scale, Line()), w};
            out.c[c] = ir().Call(IrOp::CellNoise, at, 0, Line());
        }
        return out;
    }

    // fresnel(I, N, eta, output Kr, output Kt [, output R, output T]): the dielectric Fresnel
    // reflectance of unpolarised light (Cook & Torrance, "A reflectance model for computer
    // graphics", 1982: with c = |I.N|, g^2 = 1/eta^2 + c^2 - 1,
    // Kr = (g-c)^2/(2 (g+c)^2) (1 + ((c (g+c) - 1)/(c (g-c) + 1))^2), 1 where g^2 < 0),
    // Kt = 1 - Kr, R = reflect(I, N), T = refract(I, N, eta); I and N normalised first.
    if ((e.args.size() != 5 && e.args.size() != 7) || !isVector(args[0]) || !isVector(args[1]) ||
        args[2].type != Type::Float)
        return bad(
            "(vector I, normal N, float eta, output float Kr, output float Kt [, output vector R, output "
            "vector T])");
    std::vector<Variable*> outputs;
    for (size_t i = 3; i < e.args.size(); ++i) {
        const lang::Expr& arg = *e.args[i];
        Variable* var = arg.kind == lang::ExprKind::Ident ? FindOrExtern(arg.name) : nullptr;
        const bool wantFloat = i < 5;
        if (!var || !var->writable || var->arraySize >= 0 ||
            (wantFloat ? var->type != Type::Float : !IsSpatial(var->type))) {
            m_diags.error(arg.loc, "argument " + std::to_string(i + 1) + " of 'fresnel' must be a " +
                                       (wantFloat ? "float" : "vector") + " variable (it is an output)");
            return std::nullopt;
        }
        outputs.push_back(var);
    }
    const Value i = m_ops.Normalize(m_ops.Promote(args[0], Type::Vector));
    const Value n = m_ops.Normalize(m_ops.Promote(args[1], Type::Vector));
    const Value eta = args[2], one = m_ops.Constant(1.0), zero = m_ops.Constant(0.0);
    const Value c = m_ops.Map(IrOp::Abs, m_ops.Dot(i, n));
    const Value g2 = m_ops.Sub(m_ops.Add(m_ops.Div(one, m_ops.Mul(eta, eta)), m_ops.Mul(c, c)), one);
    const Value g = m_ops.Map(IrOp::Sqrt, m_ops.Binary(IrOp::Max, g2, zero));
    const Value gMinusC = m_ops.Sub(g, c), gPlusC = m_ops.Add(g, c);
    const Value a = m_ops.Div(m_ops.Sub(m_ops.Mul(c, gPlusC), one), m_ops.Add(m_ops.Mul(c, gMinusC), one));
    const Value kr =
        m_ops.Mul(m_ops.Mul(m_ops.Constant(0.5), m_ops.Div(m_ops.Mul(gMinusC, gMinusC), m_ops.Mul(gPlusC, gPlusC))),
                  m_ops.Add(one, m_ops.Mul(a, a)));
    const Value reflectance = m_ops.SelectValue(m_ops.Binary(IrOp::Lt, g2, zero), one, kr);
    std::vector<Value> results = {reflectance, m_ops.Sub(one, reflectance)};
    if (outputs.size() == 4) {
        const Value rawI = m_ops.Promote(args[0], Type::Vector), rawN = m_ops.Promote(args[1], Type::Vector);
        results.push_back(m_ops.Sub(rawI, m_ops.Mul(m_ops.Mul(m_ops.Constant(2.0), m_ops.Dot(rawI, rawN)), rawN)));
        results.push_back(Refract(m_ops, rawI, rawN, eta));
    }
    for (size_t r = 0; r < outputs.size(); ++r) {
        Store(*outputs[r], m_ops.Promote(results[r], outputs[r]->type));
        outputs[r]->assigned = outputs[r]->used = true;
    }
    return Value{Type::Void, {}};
}

}  // namespace affray::compiler
