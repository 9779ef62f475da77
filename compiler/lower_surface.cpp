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
#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <numbers>

#include "compiler/lowerer.h"
#include "vm/lights.h"

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
    if (IsLight() && e.name == "shadow") {
        // A shadow map's occlusion: 0 (none), since affray traces a light's shadows instead
        // (LightDesc::castShadows: a light given a shadow map name casts them). The arguments
        // are still checked.
        for (const lang::ExprPtr& a : e.args)
            if (!LowerExpr(*a)) return std::nullopt;
        return m_ops.Promote(m_ops.Constant(0.0), expected == Type::Color ? Type::Color : Type::Float);
    }
    if (IsSurface() && e.name == "trace") {
        // trace(P, R): the colour seen from the shaded point along R (the renderer traces from
        // its own hit point: P is checked, not used), each channel a Trace instruction.
        std::vector<Value> args;
        for (size_t i = 0; i < e.args.size(); ++i) {
            std::optional<Value> v = LowerExpr(*e.args[i]);
            if (!v) return std::nullopt;
            if (!IsSpatial(v->type)) {
                m_diags.error(e.args[i]->loc, "argument " + std::to_string(i + 1) +
                                                  " of 'trace' must be a point, vector or normal, not " +
                                                  Article(v->type));
                return std::nullopt;
            }
            args.push_back(*v);
        }
        m_ops.SetLine(e.loc.line);
        Value seen;
        seen.type = Type::Color;
        for (int c = 0; c < 3; ++c)
            seen.c[c] = ir().Call(IrOp::Trace, {args[1].c[0], args[1].c[1], args[1].c[2]}, c, Line());
        return seen;
    }
    if (IsSurface() && (e.name == "ambient" || e.name == "diffuse" || e.name == "specular" ||
                        e.name == "specularbrdf" || e.name == "phong"))
        return LowerLighting(e);
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
        else if (IsSurface())
            m_diags.error(e.loc, "function '" + e.name +
                                     "' is not supported yet in surface shaders (affray gives them illuminance, "
                                     "ambient, diffuse, specular, specularbrdf, phong, trace and texture)");
        else if (IsLight())
            m_diags.error(e.loc, "function '" + e.name +
                                     "' is not supported yet in light shaders (affray gives them illuminate, solar, "
                                     "shadow and texture)");
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

namespace affray::compiler {

// --- surface shaders' light loops (RI Spec 3.2 sections 15.5.1 and 15.7.2)

Value Lowerer::LightVector(int slot) {
    Value L;
    L.type = Type::Vector;
    for (int i = 0; i < 3; ++i) L.c[i] = ir().Call(IrOp::Light, {False(), ir().Const(i)}, slot, Line());
    return L;
}

Value Lowerer::LightColor(int slot, ValueId shadowed) {
    Value Cl;
    Cl.type = Type::Color;
    for (int i = 0; i < 3; ++i) Cl.c[i] = ir().Call(IrOp::Light, {shadowed, ir().Const(3 + i)}, slot, Line());
    return Cl;
}

ValueId Lowerer::InCone(const Value& Ln, const Value& axisN, const Value& angle) {
    // cos(angle) <= Ln.axisN; an angle of PI or more admits every direction (the dot product of
    // two unit vectors may round below -1).
    const ValueId within =
        ir().Binary(IrOp::Le, ir().Unary(IrOp::Cos, angle.c[0], Line()), m_ops.Dot(Ln, axisN).c[0], Line());
    const ValueId all = ir().Binary(IrOp::Le, ir().Const(std::numbers::pi), angle.c[0], Line());
    return ir().Binary(IrOp::Or, all, within, Line());
}

std::vector<int> Lowerer::LightSlots(const std::string& category) {
    m_out.reads.lights = true;
    std::vector<int> slots;
    if (!m_facts) return slots;
    const bool exclude = !category.empty() && category[0] == '-';
    const std::string wanted = exclude ? category.substr(1) : category;
    for (size_t i = 0; i < m_facts->lightCategories.size() && i < size_t(vm::kMaxLightSlots); ++i) {
        // A light's __category is a comma-separated list of names.
        bool member = false;
        const std::string& list = m_facts->lightCategories[i];
        for (size_t start = 0; start <= list.size();) {
            size_t end = list.find(',', start);
            if (end == std::string::npos) end = list.size();
            member = member || list.substr(start, end - start) == wanted;
            start = end + 1;
        }
        if (wanted.empty() || member != exclude) slots.push_back(static_cast<int>(i));
    }
    return slots;
}

std::vector<Value> Lowerer::LowerLoopArguments(const lang::Expr& call, bool* ok) {
    m_line = call.loc.line;
    m_ops.SetLine(m_line);
    std::vector<Value> args;
    *ok = true;
    for (const lang::ExprPtr& a : call.args) {
        std::optional<Value> v = LowerExpr(*a);
        if (!v) *ok = false;
        args.push_back(v ? *v : m_ops.Constant(0.0));
    }
    return args;
}

void Lowerer::LowerIlluminance(const lang::Stmt& s) {
    const lang::Expr& call = *s.expr;
    bool ok = true;
    std::vector<Value> args = LowerLoopArguments(call, &ok);
    // illuminance ([string category,] point position [, vector axis, float angle]) body
    std::string category;
    size_t first = 0;
    if (ok && !args.empty() && args[0].type == Type::String) {
        std::optional<std::string> text = StringOf(args[0]);
        if (!text) {
            m_diags.error(call.args[0]->loc, "the category of 'illuminance' must be a constant string");
            ok = false;
        }
        category = text.value_or("");
        first = 1;
    }
    const size_t n = args.size() - first;
    if (ok && n != 1 && n != 3) {
        m_diags.error(call.loc, "'illuminance' expects a position, and optionally an axis and an angle" +
                                    std::string(first ? " after its category" : "") + ", got " + std::to_string(n) +
                                    " argument" + (n == 1 ? "" : "s"));
        ok = false;
    }
    auto spatial = [&](size_t i, const char* what) {
        const Type t = args[first + i].type;
        if (IsSpatial(t)) return true;
        m_diags.error(call.args[first + i]->loc, std::string("the ") + what + " of 'illuminance' must be " +
                                                     "a point, vector or normal, not " + Article(t));
        return false;
    };
    if (ok) ok = spatial(0, "position");
    if (ok && n == 3) {
        ok = spatial(1, "axis");
        if (ok && args[first + 2].type != Type::Float && args[first + 2].type != Type::Bool) {
            m_diags.error(call.args[first + 2]->loc,
                          "the angle of 'illuminance' must be a float, not " + Article(args[first + 2].type));
            ok = false;
        }
    }
    // The body is checked once as dead code when there is no light to visit (or an error). L
    // and Cl are the globals (scope 0, looked up again each time: lowering the body replaces the
    // scopes).
    auto global = [&](const char* name) -> Variable& { return m_state.scopes.front().at(name); };
    const Value outsideL = global("L").value, outsideCl = global("Cl").value;
    const std::vector<int> slots = ok ? LightSlots(category) : std::vector<int>{};
    if (slots.empty()) LowerBranches(False(), *s.body[0], nullptr);
    for (int slot : slots) {
        m_ops.SetLine(call.loc.line);
        const Value toLight = LightVector(slot);
        ValueId cond = True();
        if (n == 3) cond = InCone(m_ops.Normalize(toLight), m_ops.Normalize(args[first + 1]), args[first + 2]);
        global("L").value = toLight;
        global("Cl").value = LightColor(slot, cond);
        LowerBranches(cond, *s.body[0], nullptr);
    }
    global("L").value = outsideL;
    global("Cl").value = outsideCl;
}

bool Lowerer::IsUnit(const Value& v) const {
    if (!IsTriple(v.type)) return false;
    const IrBuilder& ir = m_out.ir;
    auto isConst = [&](ValueId x, double k) { return ir.node(x).op == IrOp::Const && ir.node(x).k == k; };
    // The operand of binary node n other than the constant k, or kNoValue.
    auto besides = [&](ValueId n, IrOp op, double k) {
        const IrNode& node = ir.node(n);
        if (node.op != op || node.count != 2) return kNoValue;
        if (isConst(node.in[0], k)) return ValueId(node.in[1]);
        if (isConst(node.in[1], k)) return ValueId(node.in[0]);
        return kNoValue;
    };
    // ValueOps::Normalize: min(max(a_i * inverse, -1), 1) with inverse = 0 < |a| ? 1 / |a| : 0 and
    // |a| = sqrt(sqr a_0 + sqr a_1 + sqr a_2), the same a and inverse for the three components.
    auto normalized = [&](const std::array<ValueId, 3>& c) {
        ValueId inverse = kNoValue;
        std::array<ValueId, 3> a{};
        for (int i = 0; i < 3; ++i) {
            const ValueId clamped = besides(c[i], IrOp::Min, 1.0);
            const ValueId product = clamped == kNoValue ? kNoValue : besides(clamped, IrOp::Max, -1.0);
            if (product == kNoValue || ir.node(product).op != IrOp::Mul) return false;
            const IrNode& mul = ir.node(product);
            // (a_i, inverse) in either order: the inverse is the operand that is a Select.
            const bool first = ir.node(mul.in[0]).op == IrOp::Select;
            const ValueId inv = first ? mul.in[0] : mul.in[1];
            a[size_t(i)] = first ? mul.in[1] : mul.in[0];
            if (i > 0 && inv != inverse) return false;
            inverse = inv;
        }
        const IrNode& select = ir.node(inverse);
        if (select.op != IrOp::Select || !isConst(select.in[2], 0.0)) return false;
        const ValueId length = besides(select.in[1], IrOp::Div, 1.0);
        if (length == kNoValue || !isConst(ir.node(select.in[1]).in[0], 1.0)) return false;
        const IrNode& root = ir.node(length);
        if (root.op != IrOp::Sqrt) return false;
        // The sum of the three squares, in any association and order.
        std::vector<ValueId> squares, stack{root.in[0]};
        while (!stack.empty() && squares.size() <= 3) {
            const ValueId x = stack.back();
            stack.pop_back();
            if (ir.node(x).op == IrOp::Add) {
                stack.push_back(ir.node(x).in[0]);
                stack.push_back(ir.node(x).in[1]);
            } else if (ir.node(x).op == IrOp::Sqr) {
                squares.push_back(ir.node(x).in[0]);
            } else {
                return false;
            }
        }
        std::sort(squares.begin(), squares.end());
        std::array<ValueId, 3> sorted = a;
        std::sort(sorted.begin(), sorted.end());
        return squares.size() == 3 && std::equal(squares.begin(), squares.end(), sorted.begin());
    };
    std::function<bool(const std::array<ValueId, 3>&, int)> unit = [&](const std::array<ValueId, 3>& c, int depth) {
        if (depth > 8) return false;
        if (normalized(c)) return true;
        const IrNode &n0 = ir.node(c[0]), &n1 = ir.node(c[1]), &n2 = ir.node(c[2]);
        if (n0.op == IrOp::Neg && n1.op == IrOp::Neg && n2.op == IrOp::Neg)
            return unit({n0.in[0], n1.in[0], n2.in[0]}, depth + 1);
        if (n0.op == IrOp::Select && n1.op == IrOp::Select && n2.op == IrOp::Select && n0.in[0] == n1.in[0] &&
            n0.in[0] == n2.in[0])
            return unit({n0.in[1], n1.in[1], n2.in[1]}, depth + 1) && unit({n0.in[2], n1.in[2], n2.in[2]}, depth + 1);
        return false;
    };
    return unit({v.c[0], v.c[1], v.c[2]}, 0);
}

void Lowerer::LowerIlluminate(const lang::Stmt& s) {
    const lang::Expr& call = *s.expr;
    const bool solar = call.name == "solar";
    bool ok = true;
    const std::vector<Value> args = LowerLoopArguments(call, &ok);
    // illuminate (point from [, vector axis, float angle]); solar (vector axis, float angle).
    const size_t n = args.size();
    if (ok && (solar ? n != 2 : n != 1 && n != 3)) {
        m_diags.error(call.loc, solar
                                    ? "'solar' expects an axis and an angle, got " + std::to_string(n) + " argument" +
                                          (n == 1 ? "" : "s") + " (a solar light without an axis is not supported yet)"
                                    : "'illuminate' expects a position, and optionally an axis and an angle, got " +
                                          std::to_string(n) + " argument" + (n == 1 ? "" : "s"));
        ok = false;
    }
    for (size_t i = 0; ok && i < n; ++i) {
        const bool angle = (solar && i == 1) || (!solar && i == 2);
        const Type t = args[i].type;
        if (angle ? (t == Type::Float || t == Type::Bool) : IsSpatial(t)) continue;
        const char* what = angle ? "angle" : (solar || i == 1) ? "axis" : "position";
        m_diags.error(call.args[i]->loc, "the " + std::string(what) + " of '" + call.name + "' must be " +
                                             (angle ? "a float" : "a point, vector or normal") + ", not " + Article(t));
        ok = false;
    }
    if (!ok) {
        LowerBranches(False(), *s.body[0], nullptr);  // checked as dead code
        return;
    }
    if (m_out.emission == LoweredShader::Emission::Ambient || solar)
        m_out.emission = solar ? LoweredShader::Emission::Solar : LoweredShader::Emission::Illuminate;
    Variable& L = m_state.scopes.front().at("L");
    ValueId cond = True();
    if (solar) {
        L.value = m_ops.Promote(args[0], Type::Vector);  // the direction the light travels
    } else {
        const Value Ps{
            Type::Point,
            {ir().Global(vm::Global::Ps, 0), ir().Global(vm::Global::Ps, 1), ir().Global(vm::Global::Ps, 2)}};
        L.value = m_ops.Promote(m_ops.Sub(Ps, args[0]), Type::Vector);
        if (n == 3) cond = InCone(m_ops.Normalize(L.value), m_ops.Normalize(args[1]), args[2]);
    }
    m_lit = ir().Binary(IrOp::Or, ir().Binary(IrOp::And, m_state.alive, cond, Line()), m_lit, Line());
    LowerBranches(cond, *s.body[0], nullptr);
}

std::optional<Value> Lowerer::LowerLighting(const lang::Expr& e) {
    std::vector<Value> args;
    for (const lang::ExprPtr& a : e.args) {
        std::optional<Value> v = LowerExpr(*a);
        if (!v) return std::nullopt;
        args.push_back(*v);
    }
    // Argument kinds: 't' a point, vector or normal, 'f' a float (kSurfaceCalls checked counts).
    const char* kinds = e.name == "diffuse"        ? "t"
                        : e.name == "specular"     ? "ttf"
                        : e.name == "specularbrdf" ? "tttf"
                        : e.name == "phong"        ? "ttf"
                                                   : "";
    for (size_t i = 0; i < args.size(); ++i) {
        const Type t = args[i].type == Type::Bool ? Type::Float : args[i].type;
        const bool fits = kinds[i] == 't' ? IsSpatial(t) : t == Type::Float;
        if (!fits) {
            m_diags.error(e.args[i]->loc, "argument " + std::to_string(i + 1) + " of '" + e.name + "' must be " +
                                              Describe(kinds[i]) + ", not " + Article(t));
            return std::nullopt;
        }
    }
    m_ops.SetLine(e.loc.line);
    const Value zero = m_ops.Promote(m_ops.Constant(0.0), Type::Color);
    if (e.name == "ambient") {
        m_out.reads.lights = true;
        return LightColor(vm::kAmbientSlot, False());
    }
    // pow(max(0, Nn.H), 1/roughness), H halfway between Ln and Vn.
    auto brdf = [&](const Value& Ln, const Value& Nn, const Value& Vn, const Value& roughness) {
        const Value H = m_ops.Normalize(m_ops.Add(Ln, Vn));
        const Value cosine = m_ops.Binary(IrOp::Max, m_ops.Constant(0.0), m_ops.Dot(Nn, H));
        return m_ops.Pow(cosine, m_ops.Div(m_ops.Constant(1.0), roughness));
    };
    if (e.name == "specularbrdf")
        return m_ops.Promote(brdf(NormalizeOnce(args[0]), NormalizeOnce(args[1]), NormalizeOnce(args[2]), args[3]),
                             Type::Color);
    // The others sum over the lights in the hemisphere about N (illuminance (P, N, PI/2)).
    const Value Nn = NormalizeOnce(args[0]);
    const Value Vn = args.size() > 1 ? NormalizeOnce(args[1]) : Nn;
    Value sum = zero;
    Value R;
    if (e.name == "phong")
        R = m_ops.Sub(m_ops.Neg(Vn),  // reflect(-Vn, Nn)
                      m_ops.Mul(m_ops.Mul(m_ops.Constant(2.0), m_ops.Dot(m_ops.Neg(Vn), Nn)), Nn));
    for (int slot : LightSlots("")) {
        const Value Ln = m_ops.Normalize(LightVector(slot));
        const ValueId cond = InCone(Ln, Nn, m_ops.Constant(std::numbers::pi / 2));
        const Value Cl = LightColor(slot, cond);
        Value weight;
        if (e.name == "diffuse")
            weight = m_ops.Dot(Ln, Nn);
        else if (e.name == "specular")
            weight = brdf(Ln, Nn, Vn, args[2]);
        else
            weight = m_ops.Pow(m_ops.Binary(IrOp::Max, m_ops.Constant(0.0), m_ops.Dot(R, Ln)), args[2]);
        sum = m_ops.SelectValue(m_ops.Float(cond), m_ops.Add(sum, m_ops.Mul(Cl, weight)), sum);
    }
    return sum;
}

}  // namespace affray::compiler
