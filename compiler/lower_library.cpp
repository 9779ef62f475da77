// compiler/lower_library.cpp: the built-ins that need more than a table row (builtins.cpp):
// noise, pnoise and cellnoise (their result type comes from the context: `float noise(P)`,
// `vector v = noise(P)`), the transforms (their space names are strings), spline (any number
// of knots, an optional basis name), filterstep (optional trailing parameter pairs) and depth
// (the instance's camera space and clipping planes).
#include <algorithm>

#include "compiler/lowerer.h"

namespace affray::compiler {

using lang::Expr;

namespace {

bool IsNoise(const std::string& name) { return name == "noise" || name == "pnoise" || name == "cellnoise"; }
bool IsTransform(const std::string& name) {
    return name == "transform" || name == "vtransform" || name == "ntransform";
}

// Spaces a shader may name: their matrices come with the instance (compiler/spaces.h; the
// renderer gives "shader", "object", "world" and "camera"), the identity where none is given
// (`affray eval`). The projective ones are not affine maps, which a bound needs.
bool IsKnownSpace(const std::string& s) {
    return s == "current" || s == "world" || s == "object" || s == "shader" || s == "camera";
}
bool IsProjectiveSpace(const std::string& s) { return s == "screen" || s == "raster" || s == "NDC"; }

}  // namespace

// The bases of RenderMan's spline (RI Spec 3.2, RiBasis), as the matrices M of
// [u^3 u^2 u 1] M [k0 k1 k2 k3]^T, and the knots each segment advances. "linear" interpolates
// between the middle two knots of each group (the first and last knots are ignored, as with
// Catmull-Rom).
const SplineBasis* FindSplineBasis(const std::string& name) {
    static const SplineBasis kBases[] = {
        {"catmull-rom", {{-0.5, 1.5, -1.5, 0.5}, {1, -2.5, 2, -0.5}, {-0.5, 0, 0.5, 0}, {0, 1, 0, 0}}, 1},
        {"bezier", {{-1, 3, -3, 1}, {3, -6, 3, 0}, {-3, 3, 0, 0}, {1, 0, 0, 0}}, 3},
        {"bspline",
         {{-1.0 / 6, 0.5, -0.5, 1.0 / 6}, {0.5, -1, 0.5, 0}, {-0.5, 0, 0.5, 0}, {1.0 / 6, 4.0 / 6, 1.0 / 6, 0}},
         1},
        {"hermite", {{2, 1, -2, 1}, {-3, -2, 3, -1}, {0, 1, 0, 0}, {1, 0, 0, 0}}, 2},
        {"power", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}, 4},
        {"linear", {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, -1, 1, 0}, {0, 1, 0, 0}}, 1},
    };
    // RiBasis spells it "b-spline"; shaders write "bspline" as often.
    const std::string canonical = name == "b-spline" ? "bspline" : name;
    for (const SplineBasis& b : kBases)
        if (canonical == b.name) return &b;
    return nullptr;
}

bool Lowerer::IsLibraryCall(const std::string& name) const {
    return IsNoise(name) || IsTransform(name) || name == "spline" || name == "filterstep" || name == "depth";
}

std::optional<std::string> Lowerer::SpaceName(const Value& v, lang::SourceLoc loc) {
    std::optional<std::string> name = StringOf(v);
    if (!name) {
        m_diags.error(loc, v.type == Type::String ? "the space name must be known when the shader is compiled "
                                                    "(here it depends on a condition)"
                                                  : "expected the name of a coordinate space, got " + Article(v.type));
        return std::nullopt;
    }
    // A space named by a parameter of a function nobody calls: any will do for checking it.
    if (Unknown(*name)) return std::string("current");
    if (IsProjectiveSpace(*name)) {
        m_diags.error(loc, "coordinate space '" + *name + "' is projective and not supported");
        return std::nullopt;
    }
    // A scene's CoordinateSystem names come with its spaces; without a scene only the standard
    // names are known (so a typo is caught when a shader is compiled on its own).
    m_out.reads.spaces.insert(*name);
    if (!IsKnownSpace(*name) && !(m_spaces && m_spaces->count(*name))) {
        m_diags.error(loc, "unknown coordinate space '" + *name + "'");
        return std::nullopt;
    }
    return name;
}

std::optional<Value> Lowerer::LowerLibraryCall(const Expr& e, std::vector<Value> args, Type expected) {
    const std::string& name = e.name;
    const int line = e.loc.line;
    for (Value& a : args)
        if (a.type == Type::Bool) a.type = Type::Float;
    auto argLoc = [&](size_t i) { return e.args[i]->loc; };

    if (IsTransform(name)) {
        // transform([from,] to, x): from `from` (else current) to current, then to `to`, which
        // is a space name or a matrix (applied to x as RenderMan does: x * m).
        if (args.size() != 2 && args.size() != 3) {
            m_diags.error(e.loc, "'" + name + "' expects 2 or 3 arguments, got " + std::to_string(args.size()));
            return std::nullopt;
        }
        std::optional<std::string> from = args.size() == 3 ? SpaceName(args[0], argLoc(0)) : "current";
        if (!from) return std::nullopt;
        const Value& toArg = args[args.size() - 2];
        const bool byMatrix = toArg.type == Type::Matrix;
        std::optional<std::string> to = byMatrix ? "" : SpaceName(toArg, argLoc(args.size() - 2));
        if (!to) return std::nullopt;
        const Value& x = args.back();
        if (!IsSpatial(x.type) && x.type != Type::Float) {
            m_diags.error(argLoc(args.size() - 1),
                          "'" + name + "' transforms a point, vector or normal, not " + Article(x.type));
            return std::nullopt;
        }
        const Type kind = name == "transform" ? Type::Point : name == "vtransform" ? Type::Vector : Type::Normal;
        const Value typed = m_ops.Promote(x, x.type == Type::Float ? kind : x.type);
        const Value inCurrent = ToCurrent(*from, typed, kind);
        if (!byMatrix) return FromCurrent(*to, inCurrent, kind);
        return m_ops.Promote(m_ops.TransformBy(toArg, inCurrent, kind), typed.type);
    }

    if (name == "depth") {
        // depth(P): P's camera-space z, 0 at the near clipping plane and 1 at the far one (RI
        // Spec 3.2 section 15.4), with the instance's planes (compiler/scene_facts.h).
        if (args.size() != 1) {
            m_diags.error(e.loc, "'depth' expects 1 argument, got " + std::to_string(args.size()));
            return std::nullopt;
        }
        if (!IsSpatial(args[0].type) && args[0].type != Type::Float) {
            m_diags.error(argLoc(0), "'depth' takes a point, not " + Article(args[0].type));
            return std::nullopt;
        }
        double nearClip = kDefaultNearClip, farClip = kDefaultFarClip;
        m_out.reads.options.insert("Clipping");
        if (m_facts) {
            if (auto it = m_facts->options.find("Clipping");
                it != m_facts->options.end() && it->second.numbers.size() == 2) {
                nearClip = it->second.numbers[0];
                farClip = it->second.numbers[1];
            }
        }
        const Value inCamera = FromCurrent("camera", m_ops.Promote(args[0], Type::Point), Type::Point);
        // (z - near) / (far - near)
        return m_ops.Div(m_ops.Sub(m_ops.Component(inCamera, 2), m_ops.Constant(nearClip)),
                         m_ops.Constant(farClip - nearClip));
    }

    if (IsNoise(name)) {
        // Coordinates: a float, two floats, a point, or a point and a float (1 to 4 dimensions);
        // pnoise then takes periods of the same shape.
        const bool periodic = name == "pnoise";
        const size_t half = periodic ? args.size() / 2 : args.size();
        auto coordinates = [&](size_t first, size_t count, std::vector<ValueId>* out) {
            if (count == 1 && args[first].type == Type::Float) {
                out->push_back(args[first].c[0]);
            } else if (count == 1 && IsSpatial(args[first].type)) {
                out->insert(out->end(), args[first].c.begin(), args[first].c.begin() + 3);
            } else if (count == 2 && args[first].type == Type::Float && args[first + 1].type == Type::Float) {
                out->push_back(args[first].c[0]);
                out->push_back(args[first + 1].c[0]);
            } else if (count == 2 && IsSpatial(args[first].type) && args[first + 1].type == Type::Float) {
                out->insert(out->end(), args[first].c.begin(), args[first].c.begin() + 3);
                out->push_back(args[first + 1].c[0]);
            } else {
                return false;
            }
            return true;
        };
        std::vector<ValueId> operands, periods;
        bool ok = (args.size() == 1 || args.size() == 2 || (periodic && args.size() == 4)) &&
                  (!periodic || args.size() % 2 == 0) && coordinates(0, half, &operands);
        if (ok && periodic) ok = coordinates(half, half, &periods) && periods.size() == operands.size();
        if (!ok) {
            std::string got;
            for (const Value& a : args) got += (got.empty() ? "" : ", ") + std::string(ToString(a.type));
            m_diags.error(e.loc,
                          "no version of '" + name + "' takes (" + got + "); expected " +
                              (periodic ? "(x, period) with x a float, two floats, a point, or a point and a float"
                                        : "a float, two floats, a point, or a point and a float"));
            return std::nullopt;
        }
        operands.insert(operands.end(), periods.begin(), periods.end());
        const IrOp op = name == "noise" ? IrOp::Noise : periodic ? IrOp::PNoise : IrOp::CellNoise;
        // The result type comes from the context: a triple context gets three independent
        // channels, anything else the float.
        const Type result = IsTriple(expected) ? expected : Type::Float;
        Value out{result, {}};
        for (int c = 0; c < 3; ++c) out.c[c] = IsTriple(result) || c == 0 ? ir().Call(op, operands, c, line) : out.c[0];
        return out;
    }

    if (name == "filterstep") {
        // filterstep(edge, x [, "param", value...]) is step(edge, x) box-filtered over the
        // width x sweeps across the surface element, |Du(x) du| + |Dv(x) dv| ("width" scales
        // it); filterstep(edge, x0, x1, ...) filters over [x0, x1].
        size_t numeric = 0;
        while (numeric < args.size() && args[numeric].type != Type::String) ++numeric;
        double widthScale = 1.0;
        for (size_t i = numeric; i < args.size(); i += 2) {
            std::optional<std::string> param = StringOf(args[i]);
            std::optional<double> v = i + 1 < args.size() ? ir().ConstValue(args[i + 1].c[0]) : std::nullopt;
            if (!param || !v || args[i + 1].type != Type::Float) {
                m_diags.error(argLoc(i), "filterstep's optional arguments are pairs of a name and a constant float");
                return std::nullopt;
            }
            if (*param == "width")
                widthScale = *v;
            else if (*param != "filter" && !Unknown(*param)) {
                m_diags.error(argLoc(i), "unknown filterstep parameter '" + *param + "'");
                return std::nullopt;
            }
        }
        if ((numeric != 2 && numeric != 3) ||
            std::any_of(args.begin(), args.begin() + numeric, [](const Value& a) { return a.type != Type::Float; })) {
            m_diags.error(e.loc, "'filterstep' expects (float edge, float x) or (float edge, float x0, float x1)");
            return std::nullopt;
        }
        const Value edge = args[0];
        Value lo, hi, width;
        if (numeric == 3) {
            lo = args[1];
            hi = args[2];
            width = m_ops.Sub(hi, lo);
        } else {
            const Value& x = args[1];
            auto global = [&](vm::Global g) { return m_ops.Float(ir().Global(g, 0)); };
            Value w = m_ops.Add(m_ops.Map(IrOp::Abs, m_ops.Mul(m_ops.Map(IrOp::DerivU, x), global(vm::Global::du))),
                                m_ops.Map(IrOp::Abs, m_ops.Mul(m_ops.Map(IrOp::DerivV, x), global(vm::Global::dv))));
            w = m_ops.Mul(w, m_ops.Constant(0.5 * widthScale));
            lo = m_ops.Sub(x, w);
            hi = m_ops.Add(x, w);
            // 2w, not hi - lo: interval and reduced affine bounds of (x + w) - (x - w) keep x's
            // width twice over, and the divisor's range would reach 0 where w's does not.
            width = m_ops.Add(w, w);
        }
        // The fraction of [lo, hi] above the edge; a zero-width filter is the plain step.
        const Value filtered =
            m_ops.Clamp(m_ops.Div(m_ops.Sub(hi, edge), width), m_ops.Constant(0.0), m_ops.Constant(1.0));
        const Value step = m_ops.Binary(IrOp::Le, edge, hi);
        return m_ops.SelectValue(m_ops.Binary(IrOp::Lt, m_ops.Constant(0.0), width), filtered, step);
    }

    // spline([basis,] t, k0, k1, ..., kn): RenderMan's spline through n+1 >= 4 knots (floats or
    // all triples), t clamped to [0, 1] spread over the n - 2 segments.
    size_t first = 0;
    std::string basis = "catmull-rom";
    if (!args.empty() && args[0].type == Type::String) {
        std::optional<std::string> b = StringOf(args[0]);
        if (!b) {
            m_diags.error(argLoc(0), "the spline basis must be known when the shader is compiled");
            return std::nullopt;
        }
        basis = Unknown(*b) ? "catmull-rom" : *b;
        first = 1;
    }
    const SplineBasis* b = FindSplineBasis(basis);
    if (!b) {
        m_diags.error(argLoc(0), "unknown spline basis '" + basis +
                                     "' (catmull-rom, bezier, bspline, hermite, power and linear are known)");
        return std::nullopt;
    }
    const size_t knotCount = args.size() - first - 1;
    if (args.size() < first + 5 || args[first].type != Type::Float) {
        m_diags.error(e.loc, "'spline' expects a float parameter and at least 4 knots");
        return std::nullopt;
    }
    if ((knotCount - 4) % static_cast<size_t>(b->step) != 0) {
        m_diags.error(e.loc, "a " + basis + " spline takes 4 + " + std::to_string(b->step) + "n knots, got " +
                                 std::to_string(knotCount));
        return std::nullopt;
    }
    Type knotType = args[first + 1].type;
    for (size_t i = first + 1; i < args.size(); ++i) {
        const bool fits = args[i].type == knotType || (IsSpatial(args[i].type) && IsSpatial(knotType)) ||
                          (args[i].type == Type::Float && IsTriple(knotType));
        if (!fits && IsTriple(args[i].type) && knotType == Type::Float)
            knotType = args[i].type;
        else if (!fits) {
            m_diags.error(argLoc(i), "spline knots must all be floats or all triples");
            return std::nullopt;
        }
    }
    std::vector<Value> knots;
    for (size_t i = first + 1; i < args.size(); ++i) knots.push_back(m_ops.Promote(args[i], knotType));
    const Value t = m_ops.Clamp(args[first], m_ops.Constant(0.0), m_ops.Constant(1.0));
    return Spline(*b, t, knots);
}

Value Lowerer::MapBy(const Matrix4& m, const Matrix4& inverse, const Value& x, Type kind) {
    Value out = x;
    for (int i = 0; i < 3; ++i) {
        // Row i of m (a point or vector), or column i of the inverse (a normal: inverse transpose).
        auto coefficient = [&](int j) { return kind == Type::Normal ? inverse[4 * j + i] : m[4 * i + j]; };
        ValueId sum = kind == Type::Point ? ir().Const(m[4 * i + 3]) : ir().Const(0.0);
        for (int j = 0; j < 3; ++j)
            sum =
                ir().Binary(IrOp::Add, sum, ir().Binary(IrOp::Mul, ir().Const(coefficient(j)), x.c[j], Line()), Line());
        out.c[i] = sum;
    }
    return out;
}

void Lowerer::NoteSpace(const std::string& space) {
    m_out.reads.spaces.insert(space);
    if (std::count(m_out.spaces.begin(), m_out.spaces.end(), space)) return;
    m_out.spaces.push_back(space);
    std::sort(m_out.spaces.begin(), m_out.spaces.end());
}

Value Lowerer::ToCurrent(const std::string& space, const Value& x, Type kind) {
    if (space == "current") return x;
    NoteSpace(space);
    if (!m_spaces || !m_spaces->count(space)) return x;  // the identity
    const SpaceTransform& t = m_spaces->at(space);
    return MapBy(t.toCurrent, t.fromCurrent, x, kind);
}

Value Lowerer::CurrentTo(const std::string& space) {
    if (space != "current") NoteSpace(space);
    if (space == "current" || !m_spaces || !m_spaces->count(space))
        return m_ops.Promote(m_ops.Constant(1.0), Type::Matrix);
    return m_ops.MatrixConstant(m_spaces->at(space).fromCurrent);
}

Value Lowerer::FromCurrent(const std::string& space, const Value& x, Type kind) {
    if (space == "current") return x;
    NoteSpace(space);
    if (!m_spaces || !m_spaces->count(space)) return x;
    const SpaceTransform& t = m_spaces->at(space);
    return MapBy(t.fromCurrent, t.toCurrent, x, kind);
}

Value Lowerer::Spline(const SplineBasis& basis, const Value& t, const std::vector<Value>& knots) {
    // RenderMan: segment s uses knots s*step .. s*step+3, and its value is
    // [u^3 u^2 u 1] * M * [k0 k1 k2 k3]^T with u the position in the segment.
    const int segments = (static_cast<int>(knots.size()) - 4) / basis.step + 1;
    const Value x = m_ops.Mul(t, m_ops.Constant(segments));
    // The segment: floor(x), with t = 1 in the last one.
    const Value segment = m_ops.Binary(IrOp::Min, m_ops.Map(IrOp::Floor, x), m_ops.Constant(segments - 1));
    const Value u = m_ops.Sub(x, segment);
    auto piece = [&](int s) {
        const Value* k = &knots[static_cast<size_t>(s) * static_cast<size_t>(basis.step)];
        Value c[4];
        for (int row = 0; row < 4; ++row) {
            c[row] = m_ops.Mul(m_ops.Constant(basis.m[row][0]), k[0]);
            for (int j = 1; j < 4; ++j) c[row] = m_ops.Add(c[row], m_ops.Mul(m_ops.Constant(basis.m[row][j]), k[j]));
        }
        // Horner: ((c0 u + c1) u + c2) u + c3
        return m_ops.Add(m_ops.Mul(m_ops.Add(m_ops.Mul(m_ops.Add(m_ops.Mul(c[0], u), c[1]), u), c[2]), u), c[3]);
    };
    Value out = piece(segments - 1);
    for (int s = segments - 2; s >= 0; --s)
        out = m_ops.SelectValue(m_ops.Binary(IrOp::Eq, segment, m_ops.Constant(s)), piece(s), out);
    return out;
}

}  // namespace affray::compiler
