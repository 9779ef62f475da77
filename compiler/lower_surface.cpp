// compiler/lower_surface.cpp: the functions and global variables of surface and light shaders
// (RI Spec 3.2, sections 15.5-15.9: ambient, diffuse, specular, texture, illuminance, Ci, L...).
// A displacement shader cannot run them (nor, in affray, the texture functions, which it may
// call), but the headers it includes often define helpers that do. So each call is type-checked
// and yields 0 of its type; it is an error only where the displacement shader runs it: not
// while checking a function nobody calls (CheckUncalledFunctions), nor in dead code. Likewise the surface globals exist only while checking such a
// function. The light loops (illuminance, illuminate, solar) reach here as an `if` on a call of
// their name (lang/parser.y), so their bodies are checked too.
// The queries a displacement shader may run (option, attribute, rendererinfo, and displacement
// or evalparam reading the shader's own parameter) fold per instance instead: the scene's facts
// (compiler/scene_facts.h) are constants of the instance, so each call is 1 and a store into its
// output variable when the name is known and the variable's type (and array size) match, else 0
// and no store (RI Spec 3.2 section 15.8; prman's rule for the types).
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
    /// Reads a texture file (environment, shadow, bump, textureinfo; texture() itself is lowered
    /// by LowerTexture): a displacement shader may call it, but affray reads none of these yet.
    bool texture = false;
    /// A query of the instance (name, output variable), folded (LowerQuery); the others are
    /// errors where the displacement shader runs them.
    bool query = false;
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
    {"surface", "so", 'f'},
    {"atmosphere", "so", 'f'},
    {"attribute", "so", 'f', false, true},
    {"option", "so", 'f', false, true},
    {"rendererinfo", "so", 'f', false, true},
    {"displacement", "so", 'f', false, true},
    {"evalparam", "so", 'f', false, true},
    {"illuminance", "?*", 'f'},
    {"illuminate", "t*", 'f'},
    {"solar", "*", 'f'},
};

struct SurfaceGlobal {
    const char* name;
    Type type;
};

constexpr SurfaceGlobal kSurfaceGlobals[] = {
    {"Cs", Type::Color},     {"Os", Type::Color},       {"Ci", Type::Color}, {"Oi", Type::Color},
    {"L", Type::Vector},     {"Cl", Type::Color},       {"Ol", Type::Color}, {"alpha", Type::Float},
    {"ncomps", Type::Float}, {"dPdtime", Type::Vector},
};

const SurfaceCall* FindSurfaceCall(const std::string& name) {
    for (const SurfaceCall& c : kSurfaceCalls)
        if (name == c.name) return &c;
    return nullptr;
}

/// What rendererinfo() knows (RI Spec 3.2 table 15.6): the version as major, minor, release,
/// patch (tools/main.cpp prints the same for `affray --version`).
std::optional<FactValue> RendererInfo(const std::string& name) {
    if (name == "renderer") return FactValue{{}, "affray"};
    if (name == "version") return FactValue{{0, 1, 0, 0}, std::nullopt};
    if (name == "versionstring") return FactValue{{}, "0.1.0"};
    return std::nullopt;
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
    if (e.name == "texture") return LowerTexture(e, expected);
    bool ok = true;
    std::optional<Value> firstValue;  // a query's name
    Variable* output = nullptr;
    for (size_t i = 0; i < e.args.size(); ++i) {
        const lang::Expr& arg = *e.args[i];
        const char want = i < fixed ? call.args[i] : '?';
        if (want == 'o') {
            // An output argument: a variable, written by the call (0 here).
            Variable* var = arg.kind == lang::ExprKind::Ident ? FindOrExtern(arg.name) : nullptr;
            if (!var) {
                m_diags.error(arg.loc, "argument " + std::to_string(i + 1) + " of '" + e.name + "' must be a variable");
                ok = false;
            } else {
                var->used = true;
                // A query writes only a known name; until then the variable keeps its state.
                if (!call.query) var->assigned = true;
                output = var;
            }
            continue;
        }
        // A texture's channel, name[1], is the name (the channel a float).
        const Variable* named = arg.kind == lang::ExprKind::Index && arg.args[0]->kind == lang::ExprKind::Ident
                                    ? FindOrExtern(arg.args[0]->name)
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
        if (i == 0) firstValue = v;
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
    if (call.query) {
        // A query's row is (name, output variable): both are set once its arguments check.
        if (!firstValue || !output) return std::nullopt;
        return LowerQuery(e, *firstValue, *output);
    }
    // Code that never runs (a function nobody calls, an arm a constant condition rules out, as
    // in `if (texname != "") ... texture(texname)` with the default "") may call it.
    const std::optional<double> alive = ir().ConstValue(m_state.alive);
    if (!m_checkingOnly && !(alive && *alive == 0.0)) {
        if (call.texture)
            m_diags.error(e.loc, "function '" + e.name + "' is not supported yet: affray reads texture() maps only");
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

namespace affray::compiler {

const Variable* Lowerer::ShaderParameter(const std::string& name) const {
    // The shader's parameters are its scope 1; inside an inlined function, the outermost
    // caller's scopes (which start after the globals) hold them.
    const std::unordered_map<std::string, Variable>* params = nullptr;
    if (m_externs.empty())
        params = m_state.scopes.size() > 1 ? &m_state.scopes[1] : nullptr;
    else if (!m_externs.front().callerScopes->empty())
        params = &m_externs.front().callerScopes->front();
    if (!params) return nullptr;
    auto it = params->find(name);
    return it == params->end() ? nullptr : &it->second;
}

std::optional<Value> Lowerer::LowerQuery(const lang::Expr& e, const Value& nameArg, Variable& out) {
    std::optional<std::string> name = StringOf(nameArg);
    if (!name) {
        m_diags.error(e.args[0]->loc, "the name given to '" + e.name +
                                          "' must be known when the shader is compiled (here it depends on a "
                                          "condition)");
        return std::nullopt;
    }
    // A function nobody calls answers nothing (the instance is unknown there).
    const Value no = m_ops.Constant(0.0), yes = m_ops.Constant(1.0);
    if (m_checkingOnly) return no;
    if (e.name == "displacement" || e.name == "evalparam") {
        // The shader's own parameter (evalparam: a shader class's, RSL 2): copied when its type
        // (and array size) is the variable's.
        const Variable* param = ShaderParameter(*name);
        if (!param || param->type != out.type || param->arraySize != out.arraySize) return no;
        if (out.arraySize >= 0) {
            for (size_t k = 0; k < out.elements.size(); ++k)
                out.elements[k] = Guard(param->elements[k], out.elements[k]);
            out.assigned = true;
        } else {
            Store(out, param->value);
        }
        return yes;
    }
    std::optional<FactValue> fact;
    if (e.name == "rendererinfo") {
        fact = RendererInfo(*name);
    } else {
        // Asked for, found or not: either way the instance depends on it (SceneReads).
        (e.name == "option" ? m_out.reads.options : m_out.reads.attributes).insert(*name);
        if (m_facts) {
            const auto& known = e.name == "option" ? m_facts->options : m_facts->attributes;
            if (auto it = known.find(*name); it != known.end()) fact = it->second;
        }
    }
    if (!fact) return no;
    // The types must match: a string, a float, or a float array of the same size.
    if (fact->text) {
        if (out.type != Type::String || out.arraySize >= 0) return no;
        Store(out, StringValue(*fact->text));
        return yes;
    }
    const size_t count = fact->numbers.size();
    if (out.type != Type::Float || (out.arraySize < 0 ? count != 1 : static_cast<size_t>(out.arraySize) != count))
        return no;
    if (out.arraySize < 0) {
        Store(out, m_ops.Constant(fact->numbers[0]));
    } else {
        for (size_t k = 0; k < count; ++k) out.elements[k] = Guard(m_ops.Constant(fact->numbers[k]), out.elements[k]);
        out.assigned = true;
    }
    return yes;
}

}  // namespace affray::compiler
