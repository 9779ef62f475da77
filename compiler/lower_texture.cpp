// compiler/lower_texture.cpp: texture() in a displacement shader (issue 16; RI Spec 3.2 section
// 15.7.1), lowered to the Texture2 and Texture8 opcodes through texture slots (vm/program.h).
// Forms:
//   texture(name[channel] [, s, t | , s1, t1, s2, t2, s3, t3, s4, t4] [, "param", value]...)
// with (s, t) the globals where no coordinate is given. A float lookup reads one channel, a color
// lookup (where the context wants a color) three, each its own slot; a one-channel map gives its
// channel to all three. The name and the parameters are compile-time constants of the instance
// (string parameters are: see LoweredShader::stringParams); the map is read here, so a missing
// file is an error at the call (a warning, and the fill value, where the call gives "fill").
// Parameters: "blur", "sblur", "tblur" (fractions of the map), "fill", "filter" ("box",
// "triangle", "gaussian", "catmull-rom"), "wrap", "swrap", "twrap" ("black", "clamp",
// "periodic"; the map's own wrap modes otherwise); "width", "swidth", "twidth" and "samples"
// are accepted and have no effect: affray has no ray footprint to scale a filter by, so a lookup
// is the plain (bilinear) one, blurred as asked, which "width" 0 also means.
// Files are found as given if absolute, else in the scene's texture search path
// (SceneFacts::textureSearchPath), the shader's directory, then the working directory.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "compiler/lowerer.h"
#include "vm/interpreter.h"

namespace affray::compiler {

namespace {

/// The file `name` names, as the header says; nothing if there is none, with *where set to the
/// places looked in.
std::optional<std::string> ResolveTexture(const std::string& name, const std::string& shaderPath,
                                          const SceneFacts* facts, std::string* where) {
    namespace fs = std::filesystem;
    std::error_code ec;
    auto isFile = [&](const fs::path& p) { return fs::exists(p, ec) && !fs::is_directory(p, ec); };
    const fs::path given(name);
    if (name.empty()) {
        *where = "the name is empty";
        return std::nullopt;
    }
    if (given.is_absolute()) {
        *where = "no such file";
        if (isFile(given)) return name;
        return std::nullopt;
    }
    std::vector<fs::path> dirs;
    if (facts)
        for (const std::string& d : facts->textureSearchPath) dirs.emplace_back(d);
    dirs.push_back(fs::path(shaderPath).parent_path());
    for (const fs::path& dir : dirs) {
        const fs::path candidate = dir / given;
        if (isFile(candidate)) return candidate.lexically_normal().string();
    }
    if (isFile(given)) return name;
    *where = "looked in ";
    for (const fs::path& dir : dirs)
        if (!dir.empty()) *where += "'" + dir.string() + "', ";
    *where += "the working directory";
    return std::nullopt;
}

std::string FormatFill(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

}  // namespace

std::optional<double> Lowerer::OptionValue(ValueId v, std::vector<std::string>* params) const {
    const IrNode& n = m_out.ir.node(v);
    switch (n.op) {
        case IrOp::Const: return n.k;
        case IrOp::Global: return std::nullopt;
        case IrOp::Param: {
            // A generic program's parameter: its default (the instance is lowered again with its value).
            const ParamInfo& p = m_out.params.at(n.in[0]);
            if (params) params->push_back(p.name);
            if (n.in[1] >= p.defaults.size()) return std::nullopt;
            return p.defaults[n.in[1]];
        }
        default: break;
    }
    const vm::Operation f = OperationOf(n.op);
    if (!vm::Has(f, vm::kFoldable)) return std::nullopt;
    double x[kMaxIrOperands];
    for (int i = 0; i < n.count; ++i) {
        std::optional<double> k = OptionValue(n.in[i], params);
        if (!k) return std::nullopt;
        x[i] = *k;
    }
    const vm::Op op = vm::OpcodeFor(f, n.count, vm::OperandForm::RR);
    if (op == vm::Op::Ext) return std::nullopt;
    return vm::RunScalarOpcode(op, x, n.channel);
}

std::optional<Value> Lowerer::LowerTexture(const lang::Expr& e, Type expected) {
    bool ok = true;
    // The name, and its channel: name[channel].
    const lang::Expr& nameArg = *e.args[0];
    const bool indexed = nameArg.kind == lang::ExprKind::Index;
    std::optional<Value> nameValue = LowerExpr(indexed ? *nameArg.args[0] : nameArg);
    std::optional<std::string> name = nameValue ? StringOf(*nameValue) : std::nullopt;
    if (nameValue && !name)
        m_diags.error(nameArg.loc, "the texture name must be a constant string (a literal or a string parameter)");
    // No name (an unknown identifier, already reported), no lookup: *name is read below.
    if (!name) ok = false;
    int channel = 0;
    std::vector<std::string> dependsOn;  // parameters the options were taken from (their defaults)
    if (indexed) {
        std::optional<Value> c = LowerExpr(*nameArg.args[1]);
        std::optional<double> k = c && c->type == Type::Float ? OptionValue(c->c[0], &dependsOn) : std::nullopt;
        if (c && !(k && *k >= 0 && *k < 65536 && *k == std::floor(*k))) {
            m_diags.error(nameArg.args[1]->loc, "the texture channel must be a constant whole number from 0");
            ok = false;
        } else if (k) {
            channel = static_cast<int>(*k);
        }
    }
    // The coordinates: the floats before the first string.
    size_t i = 1;
    std::vector<ValueId> coords;
    for (; i < e.args.size(); ++i) {
        std::optional<Value> v = LowerExpr(*e.args[i]);
        if (!v) {
            ok = false;
            continue;
        }
        if (v->type == Type::String) break;
        if (v->type != Type::Float && v->type != Type::Bool) {
            m_diags.error(e.args[i]->loc, "texture coordinates must be floats, not " + Article(v->type));
            ok = false;
        }
        coords.push_back(v->c[0]);
    }
    if (coords.empty()) {
        coords = {ir().Global(vm::Global::s, 0), ir().Global(vm::Global::t, 0)};
    } else if (coords.size() != 2 && coords.size() != 8 && ok) {
        m_diags.error(e.loc, "texture() takes s and t, four corners (8 floats) or no coordinates, got " +
                                 std::to_string(coords.size()) + (coords.size() == 1 ? " float" : " floats"));
        ok = false;
    }
    // The parameters: ("name", value) pairs.
    texture::LookupOptions options;
    options.channel = channel;
    bool hasFill = false;
    std::optional<texture::Wrap> swrap, twrap;
    for (; i < e.args.size(); i += 2) {
        const lang::Expr& keyArg = *e.args[i];
        std::optional<Value> key = LowerExpr(keyArg);
        std::optional<std::string> keyText = key ? StringOf(*key) : std::nullopt;
        if (i + 1 >= e.args.size() || !keyText) {
            m_diags.error(keyArg.loc, "texture parameters come in pairs: a constant name, then its value");
            ok = false;
            break;
        }
        const lang::Expr& valueArg = *e.args[i + 1];
        std::optional<Value> value = LowerExpr(valueArg);
        if (!value) {
            ok = false;
            continue;
        }
        const std::string& p = *keyText;
        if (p == "filter" || p == "wrap" || p == "swrap" || p == "twrap") {
            std::optional<std::string> text = StringOf(*value);
            texture::Wrap w{};
            texture::Filter f{};
            const bool known =
                text && (p == "filter" ? texture::ParseFilter(*text, &f) : texture::ParseWrap(*text, &w));
            if (!known) {
                m_diags.error(valueArg.loc, "texture parameter '" + p + "' must be a constant string naming a " +
                                                (p == "filter" ? "filter (box, triangle, gaussian, catmull-rom)"
                                                               : "wrap mode (black, clamp, periodic)"));
                ok = false;
            } else if (p == "filter") {
                options.filter = f;
            } else {
                if (p != "twrap") swrap = w;
                if (p != "swrap") twrap = w;
            }
            continue;
        }
        const bool numeric = p == "blur" || p == "sblur" || p == "tblur" || p == "fill" || p == "width" ||
                             p == "swidth" || p == "twidth" || p == "samples";
        if (!numeric) {
            m_diags.warning(keyArg.loc, "unknown texture parameter '" + p + "' ignored");
            continue;
        }
        const bool isFloat = value->type == Type::Float || value->type == Type::Bool;
        if (p == "width" || p == "swidth" || p == "twidth" || p == "samples") {
            // No effect (see the header), so any float will do, varying ones too.
            if (!isFloat) {
                m_diags.error(valueArg.loc,
                              "texture parameter '" + p + "' must be a float, not " + Article(value->type));
                ok = false;
            }
            continue;
        }
        std::optional<double> k = isFloat ? OptionValue(value->c[0], &dependsOn) : std::nullopt;
        if (!k || !std::isfinite(*k) || (p != "fill" && *k < 0)) {
            m_diags.error(valueArg.loc, "texture parameter '" + p + "' must be a constant " +
                                            (p == "fill" ? "float" : "float >= 0") +
                                            " (a literal, or computed from parameters)");
            ok = false;
            continue;
        }
        if (p == "blur") options.sblur = options.tblur = *k;
        if (p == "sblur") options.sblur = *k;
        if (p == "tblur") options.tblur = *k;
        if (p == "fill") options.fill = *k, hasFill = true;
    }
    if (!ok) return std::nullopt;
    const bool color = expected == Type::Color;
    // A function nobody calls, or code that never runs (an arm a constant condition rules out, as
    // in `if (texname != "") ... texture(texname)` with the default ""), reads no file.
    const std::optional<double> alive = ir().ConstValue(m_state.alive);
    if (m_checkingOnly || (alive && *alive == 0.0))
        return m_ops.Promote(m_ops.Constant(0.0), color ? Type::Color : Type::Float);

    // The map, read once per file by the process-wide cache.
    std::string why;
    m_out.reads.textureSearchPath = true;
    const std::optional<std::string> found = ResolveTexture(*name, m_diags.file().path(), m_facts, &why);
    const std::string path = found.value_or(*name);
    std::shared_ptr<const texture::TextureMap> map;
    if (found)
        map = texture::Open(path, &why);
    else
        why = "cannot find texture '" + *name + "' (" + why + ")";
    // The generic programs are lowered with the parameters' defaults, whose map the scene may
    // replace: a map named by a parameter that they cannot read is the instance's to report
    // (compile.cpp lowers it with the same defaults when the scene gives no other), and the
    // generic slot has no map. A literal name is every instance's: reported here, with the
    // shader's other errors.
    const bool literal = (indexed ? *nameArg.args[0] : nameArg).kind == lang::ExprKind::String;
    const bool generic = m_paramValues == nullptr && !literal;
    if (!map && !hasFill && !generic) {
        m_diags.error(nameArg.loc, why);
        return std::nullopt;
    }
    if (!map && !generic)
        m_diags.warning(nameArg.loc, why + "; its lookups give the fill value " + FormatFill(options.fill));
    options.swrap = swrap.value_or(map ? map->swrap() : texture::Wrap::Periodic);
    options.twrap = twrap.value_or(map ? map->twrap() : texture::Wrap::Periodic);
    if (map && map->nonFiniteTexels() > 0 && !generic)
        m_diags.warning(nameArg.loc, "texture '" + path + "' has " + std::to_string(map->nonFiniteTexels()) +
                                         " texels that are NaN or infinite: they are read as 0");
    if (map && channel >= map->channels() && !generic)
        m_diags.warning(nameArg.loc, "texture '" + path + "' has " + std::to_string(map->channels()) +
                                         " channel(s): channel " + std::to_string(channel) + " gives the fill value");

    Value out = m_ops.Promote(m_ops.Constant(0.0), color ? Type::Color : Type::Float);
    for (int c = 0; c < (color ? 3 : 1); ++c) {
        vm::TextureSlot slot;
        slot.path = path;
        slot.options = options;
        slot.options.channel = map && map->channels() == 1 && channel == 0 ? 0 : channel + c;
        slot.fillIfMissing = hasFill;
        slot.map = map;
        slot.dependsOn = dependsOn;
        const std::optional<int> index = TextureSlotIndex(slot);
        if (!index) {
            m_diags.error(e.loc, "too many distinct texture lookups in one shader (at most " +
                                     std::to_string(vm::kMaxTextureSlots) + ")");
            return std::nullopt;
        }
        out.c[c] = ir().Call(IrOp::Texture, coords, *index, Line());
    }
    if (!color) out.c[1] = out.c[2] = out.c[0];
    return out;
}

std::optional<int> Lowerer::TextureSlotIndex(const vm::TextureSlot& slot) {
    std::vector<vm::TextureSlot>& slots = m_out.textures;
    for (size_t i = 0; i < slots.size(); ++i) {
        vm::TextureSlot& s = slots[i];
        const texture::LookupOptions &a = s.options, &b = slot.options;
        if (s.path == slot.path && a.channel == b.channel && a.swrap == b.swrap && a.twrap == b.twrap &&
            a.filter == b.filter && a.sblur == b.sblur && a.tblur == b.tblur && a.fill == b.fill &&
            s.fillIfMissing == slot.fillIfMissing && s.map == slot.map) {
            for (const std::string& p : slot.dependsOn)
                if (std::find(s.dependsOn.begin(), s.dependsOn.end(), p) == s.dependsOn.end()) s.dependsOn.push_back(p);
            return static_cast<int>(i);
        }
    }
    if (slots.size() >= static_cast<size_t>(vm::kMaxTextureSlots)) return std::nullopt;
    slots.push_back(slot);
    return static_cast<int>(slots.size() - 1);
}

}  // namespace affray::compiler
