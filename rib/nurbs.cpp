// rib/nurbs.cpp: NuPatch and TrimCurve (RI Spec 3.2 section 5.3). A NuPatch is checked (orders
// 2..kMaxNurbsOrder, n >= order, n + order nondecreasing knots, min < max within the knots'
// range, positive weights, the counts of every primitive variable by storage class) and cut into
// one rational patch per non-empty knot span (renderer::SplitNurbs), each a primitive covering
// its part of the NuPatch's (u,v) (the knot parameters), cut by the TrimCurve in effect. A span
// that the trim curves remove entirely becomes no primitive.
#include <algorithm>
#include <cmath>

#include "rib/parser.h"

namespace affray::rib {

using renderer::KnotVector;
using renderer::NurbsST;
using renderer::StorageClass;
using renderer::TrimCurves;

bool RibParser::AddRational(const RibRequest& r, const std::string& context, const renderer::RationalPatch& patch,
                            const renderer::ParameterRange& range, std::shared_ptr<const TrimCurves> trim) {
    if (!patch.FiniteP()) return Fail(r.at, context + " overflows in world space");
    PrimitiveDesc prim;
    prim.base = renderer::BaseSurface(patch, false, range, std::move(trim));
    SetPrimitiveAttributes(r, &prim);
    m_scene.primitives.push_back(std::move(prim));
    return true;
}

// NuPatch nu uorder uknot umin umax nv vorder vknot vmin vmax ...parameters
bool RibParser::DoNuPatch(const RibRequest& r) {
    const std::string context = "'NuPatch'";
    if (r.args.size() < 10)
        return Fail(r.at, context + " expects nu uorder uknot umin umax nv vorder vknot vmin vmax, got " +
                              std::to_string(r.args.size()) + " arguments");
    KnotVector k[2];
    for (int axis = 0; axis < 2; ++axis) {
        const size_t first = axis == 0 ? 0 : 5;
        const std::string d = axis == 0 ? "u" : "v";
        double scalar[4];  // n, order, min, max
        const size_t at[4] = {first, first + 1, first + 3, first + 4};
        const std::string names[4] = {"n" + d, d + "order", d + "min", d + "max"};
        for (int i = 0; i < 4; ++i) {
            const RibArg& a = r.args[at[i]];
            if (!a.NumericP() || a.numbers.size() != 1 || !std::isfinite(a.numbers[0]))
                return Fail(a.at, context + ": " + names[i] + " must be a number, got " + a.Describe());
            scalar[i] = a.numbers[0];
            if (i < 2 && (scalar[i] != std::floor(scalar[i]) || scalar[i] < 1 || scalar[i] > 1e6))
                return Fail(a.at, context + ": " + names[i] + " must be a positive integer, got " + a.Describe());
        }
        const RibArg& knots = r.args[first + 2];
        if (!knots.NumericP())
            return Fail(knots.at, context + ": " + d + "knot must be numbers, got " + knots.Describe());
        k[axis] = KnotVector{int(scalar[0]), int(scalar[1]), knots.numbers, scalar[2], scalar[3]};
        if (std::string problem = k[axis].Problem(d); !problem.empty()) return Fail(knots.at, context + ": " + problem);
    }
    std::vector<RibParam> params;
    m_uniformVaries = true;
    const bool listed = ParamList(r, 10, &params);
    m_uniformVaries = false;
    if (!listed || !InsideWorld(r)) return false;

    renderer::NurbsSurface surface{k[0], k[1], {}, std::nullopt, std::nullopt, std::nullopt};
    const size_t nPoints = size_t(k[0].n) * size_t(k[1].n);
    const size_t segU = size_t(k[0].n) - size_t(k[0].order) + 1, segV = size_t(k[1].n) - size_t(k[1].order) + 1;
    const RibParam *position = nullptr, *st = nullptr, *s = nullptr, *t = nullptr;
    for (const RibParam& p : params) {
        const std::string& n = p.value.name;
        if (n == "P" || n == "Pw")
            position = &p;
        else if (n == "st")
            st = &p;
        else if (n == "s")
            s = &p;
        else if (n == "t")
            t = &p;
        else if (n != "Cs" && n != "Os")  // read below
            Warn(p.at, context + " parameter " + Quote(n) + " is not supported yet; ignored");
    }
    if (!position) return Fail(r.at, context + " needs a \"P\" or \"Pw\" parameter");
    const size_t width = position->value.name == "P" ? 3 : 4;
    std::vector<double> v(width * nPoints);
    if (!ParamNumbers(*position, context, width * nPoints, v.data())) return false;
    for (size_t i = 0; i < nPoints; ++i) {
        const double w = width == 4 ? v[4 * i + 3] : 1.0;
        if (!(w > 0) || !std::isfinite(w))
            return Fail(position->at, context + " parameter 'Pw': point " + std::to_string(i) +
                                          " has w = " + FormatNumber(w) + "; NURBS weights must be positive");
        surface.points.emplace_back(v[width * i], v[width * i + 1], v[width * i + 2], w);
    }

    // Texture coordinates: "st", or "s" and "t" together, of one storage class.
    if (st || s || t) {
        if (st && (s || t)) return Fail((s ? s : t)->at, context + " takes \"st\" or \"s\" and \"t\", not both");
        if (!st && !(s && t))
            return Fail((s ? s : t)->at,
                        context + " needs both \"s\" and \"t\" (or \"st\"): one alone is not supported");
        NurbsST coords;
        const RibParam* parts[2] = {st ? st : s, st ? nullptr : t};
        for (const RibParam* p : parts) {
            if (!p) continue;
            const std::string declared =
                p->value.declaration.empty() ? StandardDeclaration(p->value.name) : p->value.declaration;
            RibDeclaration d;
            std::string problem;
            if (!RibDeclaration::Parse(declared, &d, &problem)) return Fail(p->at, context + " parameter: " + problem);
            ResolveStorage(*p, context, {segU * segV, nPoints, 0, (segU + 1) * (segV + 1)}, false, &d);
            const std::optional<StorageClass> storage =
                d.Storage() == StorageClass::FaceVarying ? std::nullopt : std::optional(d.Storage());
            if (!storage)
                return Fail(p->at, context + " parameter " + Quote(p->value.name) + ": storage class " +
                                       Quote(d.storage) + " is not defined on a NuPatch");
            if (p == parts[1] && *storage != coords.storage)
                return Fail(p->at, context + " parameters 's' and 't' must have the same storage class");
            coords.storage = *storage;
            const size_t entries = *storage == StorageClass::Constant  ? 1
                                   : *storage == StorageClass::Uniform ? segU * segV
                                   : *storage == StorageClass::Varying ? (segU + 1) * (segV + 1)
                                                                       : nPoints;
            const size_t each = st ? 2 : 1;
            if (d.UniformCount() != each)
                return Fail(p->at, context + " parameter " + Quote(p->value.name) + " must be " +
                                       (st ? "float[2]" : "float") + ", declared " + Quote(declared));
            std::vector<double> values(entries * each);
            if (!ParamNumbers(*p, context, entries * each, values.data())) return false;
            coords.values.resize(entries, glm::dvec2(0.0));
            for (size_t i = 0; i < entries; ++i) {
                if (st)
                    coords.values[i] = glm::dvec2(values[2 * i], values[2 * i + 1]);
                else
                    coords.values[i][p == parts[0] ? 0 : 1] = values[i];
            }
        }
        surface.st = std::move(coords);
    }

    // Colours, counted as st is (no facevarying class on a NuPatch).
    for (const RibParam& p : params) {
        if (p.value.name != "Cs" && p.value.name != "Os") continue;
        ColorValues c;
        if (!ColorPrimvar(p, context, {segU * segV, nPoints, 0, (segU + 1) * (segV + 1)}, false, &c)) return false;
        (p.value.name == "Cs" ? surface.Cs : surface.Os) = renderer::NurbsColor{c.storage, std::move(c.values)};
    }

    // The trim curves in effect, with the current sense.
    std::shared_ptr<const TrimCurves> trim = m_state.trim;
    if (trim && trim->keepInside != m_state.trimKeepInside) {
        auto flipped = std::make_shared<TrimCurves>(*trim);
        flipped->keepInside = m_state.trimKeepInside;
        trim = std::move(flipped);
    }
    for (const renderer::NurbsSpan& span : renderer::SplitNurbs(surface, m_state.ctm)) {
        const renderer::ParameterRange& g = span.range;
        if (trim && trim->RemovedP(g.u0, g.u1, g.v0, g.v1)) continue;
        if (!AddRational(r, context, span.patch, span.range, trim)) return false;
        if (span.Cs) m_scene.primitives.back().SetColor(0, *span.Cs);
        if (span.Os) m_scene.primitives.back().SetColor(1, *span.Os);
    }
    return true;
}

// TrimCurve [ncurves] [order] [knot] [min] [max] [n] [u] [v] [w] (the RIB binding; nloops, the
// length of ncurves, may also be given first, as the C binding has it). Attribute state: the
// loops cut every NuPatch that follows in the attribute block. Empty arrays remove the trim.
bool RibParser::DoTrimCurve(const RibRequest& r) {
    const std::string context = "'TrimCurve'";
    size_t first = 0;
    if (r.args.size() == 10 && !r.args[0].isArray) first = 1;
    if (r.args.size() != 9 + first)
        return Fail(r.at, context + " expects ncurves order knot min max n u v w, got " +
                              std::to_string(r.args.size()) + " arguments");
    for (size_t i = 0; i < r.args.size(); ++i)
        if (!r.args[i].NumericP()) return Fail(r.args[i].at, context + " expects numbers, got " + r.args[i].Describe());
    if (r.args[first].numbers.empty()) {
        m_state.trim = nullptr;
        return true;
    }
    std::vector<int> ncurves, order, n;
    if (!IntArray(r, first, "ncurves", 1, &ncurves) || !IntArray(r, first + 1, "order", 2, &order) ||
        !IntArray(r, first + 5, "n", 2, &n))
        return false;
    if (first == 1 && r.args[0].numbers[0] != double(ncurves.size()))
        return Fail(r.args[0].at, context + " nloops is " + FormatNumber(r.args[0].numbers[0]) + " but ncurves has " +
                                      std::to_string(ncurves.size()) + " entries");
    size_t curves = 0;
    for (int c : ncurves) curves += size_t(c);
    const std::vector<double>& knot = r.args[first + 2].numbers;
    const std::vector<double>&min = r.args[first + 3].numbers, &max = r.args[first + 4].numbers;
    const std::vector<double>&u = r.args[first + 6].numbers, &v = r.args[first + 7].numbers,
          &w = r.args[first + 8].numbers;
    auto count = [&](size_t index, const char* what, size_t want, size_t got) {
        return want == got ? true
                           : Fail(r.args[first + index].at, context + " " + what + " has " + std::to_string(got) +
                                                                " values; the curves need " + std::to_string(want));
    };
    size_t knots = 0, points = 0;
    for (size_t c = 0; c < std::min({curves, order.size(), n.size()}); ++c)
        knots += size_t(n[c] + order[c]), points += size_t(n[c]);
    if (!count(1, "order", curves, order.size()) || !count(5, "n", curves, n.size()) ||
        !count(3, "min", curves, min.size()) || !count(4, "max", curves, max.size()) ||
        !count(2, "knot", knots, knot.size()) || !count(6, "u", points, u.size()) || !count(7, "v", points, v.size()) ||
        !count(8, "w", points, w.size()))
        return false;
    // Each curve checked; the tolerance of the flattening is 1e-6 of the trim's extent in (u,v).
    std::vector<KnotVector> vectors;
    std::vector<std::vector<glm::dvec3>> controls;
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    size_t nextKnot = 0, nextPoint = 0;
    for (size_t c = 0; c < curves; ++c) {
        KnotVector kv{n[c], order[c], {}, min[c], max[c]};
        kv.knots.assign(knot.begin() + long(nextKnot), knot.begin() + long(nextKnot + size_t(n[c] + order[c])));
        if (std::string problem = kv.Problem("trim curve " + std::to_string(c)); !problem.empty())
            return Fail(r.args[first + 2].at, context + ": " + problem);
        std::vector<glm::dvec3> uvw;
        for (size_t i = nextPoint; i < nextPoint + size_t(n[c]); ++i) {
            if (!(w[i] > 0) || !std::isfinite(w[i]) || !std::isfinite(u[i]) || !std::isfinite(v[i]))
                return Fail(r.args[first + 8].at, context + " point " + std::to_string(i) + " has w = " +
                                                      FormatNumber(w[i]) + "; trim curve weights must be positive");
            uvw.emplace_back(u[i], v[i], w[i]);
            lo = glm::min(lo, glm::dvec2(u[i], v[i]) / w[i]);
            hi = glm::max(hi, glm::dvec2(u[i], v[i]) / w[i]);
        }
        nextKnot += kv.knots.size();
        nextPoint += size_t(n[c]);
        vectors.push_back(std::move(kv));
        controls.push_back(std::move(uvw));
    }
    const double tolerance = 1e-6 * std::max({hi.x - lo.x, hi.y - lo.y, 1e-300});
    auto trim = std::make_shared<TrimCurves>();
    size_t c = 0;
    for (int loopCurves : ncurves) {
        std::vector<glm::dvec2> loop;
        for (int i = 0; i < loopCurves; ++i, ++c) renderer::FlattenTrimCurve(vectors[c], controls[c], tolerance, &loop);
        trim->loops.push_back(std::move(loop));
    }
    m_state.trim = std::move(trim);
    return true;
}

}  // namespace affray::rib
