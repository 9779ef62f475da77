// compiler/lower_surface.cpp: the functions and global variables of surface and light shaders
// (RI Spec 3.2, sections 15.5-15.9: ambient, diffuse, specular, texture, illuminance, Ci, L...).
// A displacement shader cannot run them (nor, in affray, the texture functions, which it may
// call), but the headers it includes often define helpers that do. So each call is type-checked
// and yields 0 of its type; it is an error only where the displacement shader runs it: not
// while checking a function nobody calls (CheckUncalledFunctions), nor in dead code. Likewise the surface globals exist only while checking such a
// function. The light loops (illuminance, illuminate, solar) reach here as an `if` on a call of
// their name (lang/parser.y), so their bodies are checked too.
// To add a function: a row in kSurfaceCalls (argument letters below, then the result).
#include <cstring>

#include "compiler/lowerer.h"

namespace affray::compiler {

namespace {

struct SurfaceCall {
    const char* name;
    /// Arguments: 's' string, 't' point/vector/normal (or float), 'f' float, '?' any type,
    /// 'o' an output variable; a trailing '*' allows more of any type (texture's parameters).
    const char* args;
    /// 'c' color, 'f' float, 'x' float or color as the context wants (texture, environment).
    char result;
    /// Reads a texture file: a displacement shader may call it, but affray reads none yet.
    bool texture = false;
};

constexpr SurfaceCall kSurfaceCalls[] = {
    {"ambient", "", 'c'},
    {"diffuse", "t", 'c'},
    {"specular", "ttf", 'c'},
    {"specularbrdf", "tttf", 'c'},
    {"phong", "ttf", 'c'},
    {"trace", "tt", 'c'},
    {"texture", "s*", 'x', true},
    {"environment", "s*", 'x', true},
    {"shadow", "s*", 'f', true},
    {"bump", "s*", 'f', true},
    {"textureinfo", "sso", 'f', true},
    {"lightsource", "so", 'f'},
    {"incident", "so", 'f'},
    {"opposite", "so", 'f'},
    {"attribute", "so", 'f'},
    {"option", "so", 'f'},
    {"rendererinfo", "so", 'f'},
    {"illuminance", "?*", 'f'},
    {"illuminate", "t*", 'f'},
    {"solar", "*", 'f'},
};

struct SurfaceGlobal {
    const char* name;
    Type type;
};

constexpr SurfaceGlobal kSurfaceGlobals[] = {
    {"Cs", Type::Color},     {"Os", Type::Color},    {"Ci", Type::Color},       {"Oi", Type::Color},
    {"L", Type::Vector},     {"Cl", Type::Color},    {"Ol", Type::Color},       {"alpha", Type::Float},
    {"ncomps", Type::Float}, {"dtime", Type::Float}, {"dPdtime", Type::Vector},
};

const SurfaceCall* FindSurfaceCall(const std::string& name) {
    for (const SurfaceCall& c : kSurfaceCalls)
        if (name == c.name) return &c;
    return nullptr;
}

const char* Describe(char letter) {
    switch (letter) {
        case 's': return "a string";
        case 't': return "a point, vector or normal";
        case 'f': return "a float";
        case 'o': return "a variable";
    }
    return "a value";
}

}  // namespace

bool Lowerer::IsSurfaceCall(const std::string& name) { return FindSurfaceCall(name) != nullptr; }

Type Lowerer::SurfaceGlobalType(const std::string& name) {
    for (const SurfaceGlobal& g : kSurfaceGlobals)
        if (name == g.name) return g.type;
    return Type::Void;
}

void Lowerer::AddSurfaceGlobals(std::unordered_map<std::string, Variable>& scope) {
    for (const SurfaceGlobal& g : kSurfaceGlobals) {
        Variable var;
        var.type = g.type;
        var.value = m_ops.Promote(m_ops.Constant(0.0), g.type);
        var.assigned = var.used = var.isGlobal = true;
        scope.emplace(g.name, var);
    }
}

std::vector<std::string> SurfaceCallNames() {
    std::vector<std::string> names;
    for (const SurfaceCall& c : kSurfaceCalls) names.emplace_back(c.name);
    return names;
}

std::optional<Value> Lowerer::LowerSurfaceCall(const lang::Expr& e, Type expected) {
    const SurfaceCall& call = *FindSurfaceCall(e.name);
    const size_t fixed = std::strlen(call.args) - (std::strchr(call.args, '*') ? 1 : 0);
    const bool more = fixed != std::strlen(call.args);
    if (e.args.size() < fixed || (!more && e.args.size() > fixed)) {
        m_diags.error(e.loc, "'" + e.name + "' expects " + (more ? "at least " : "") + std::to_string(fixed) +
                                 " argument" + (fixed == 1 ? "" : "s") + ", got " + std::to_string(e.args.size()));
        return std::nullopt;
    }
    bool ok = true;
    for (size_t i = 0; i < e.args.size(); ++i) {
        const lang::Expr& arg = *e.args[i];
        const char want = i < fixed ? call.args[i] : '?';
        if (want == 'o') {
            // An output argument: a variable, written by the call (0 here).
            Variable* var = arg.kind == lang::ExprKind::Ident ? Find(arg.name) : nullptr;
            if (!var) {
                m_diags.error(arg.loc, "argument " + std::to_string(i + 1) + " of '" + e.name + "' must be a variable");
                ok = false;
            } else {
                var->used = true;
                var->assigned = true;
            }
            continue;
        }
        // A texture's channel, name[1], is the name (the channel a float).
        const Variable* named = arg.kind == lang::ExprKind::Index && arg.args[0]->kind == lang::ExprKind::Ident
                                    ? Find(arg.args[0]->name)
                                    : nullptr;
        const bool channel = arg.kind == lang::ExprKind::Index &&
                             (arg.args[0]->kind == lang::ExprKind::String || (named && named->type == Type::String));
        if (channel && !LowerExpr(*arg.args[1])) {
            ok = false;
            continue;
        }
        std::optional<Value> v = LowerExpr(channel ? *arg.args[0] : arg);
        if (!v) {
            ok = false;
            continue;
        }
        const Type t = v->type == Type::Bool ? Type::Float : v->type;
        const bool fits = want == '?' || (want == 's' && t == Type::String) || (want == 'f' && t == Type::Float) ||
                          (want == 't' && (IsSpatial(t) || t == Type::Float));
        if (!fits) {
            m_diags.error(arg.loc, "argument " + std::to_string(i + 1) + " of '" + e.name + "' must be " +
                                       Describe(want) + ", not " + Article(t));
            ok = false;
        }
    }
    if (!ok) return std::nullopt;
    // Code that never runs (a function nobody calls, an arm a constant condition rules out, as
    // in `if (texname != "") ... texture(texname)` with the default "") may call it.
    const std::optional<double> alive = ir().ConstValue(m_state.alive);
    if (!m_checkingOnly && !(alive && *alive == 0.0)) {
        if (call.texture)
            m_diags.error(e.loc, "function '" + e.name + "' is not supported yet: affray reads no texture files");
        else
            m_diags.error(
                e.loc,
                "'" + e.name + "' is a function of surface and light shaders: a displacement shader cannot call it");
        return std::nullopt;
    }
    const Type result = call.result == 'c'                              ? Type::Color
                        : call.result == 'x' && expected == Type::Color ? Type::Color
                                                                        : Type::Float;
    return m_ops.Promote(m_ops.Constant(0.0), result);
}

}  // namespace affray::compiler
