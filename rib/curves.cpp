// rib/curves.cpp: Curves, as tubes. A curve is drawn as the surface its width sweeps around it: a
// linear curve as one truncated cone (a Hyperboloid quadric) per segment between its vertices,
// exactly; a cubic curve (the v basis and step of Basis) as kCubicPieces such cones a span, between
// points of the curve (an approximation: a note says how far the chords stray from the curve).
// prman draws curves as flat ribbons facing the camera: the same silhouette, a tube's shading (a
// note says so once). Widths are in object space, as RI 3.2 gives them.
#include <algorithm>
#include <cmath>

#include "rib/parser.h"

namespace affray::rib {

using renderer::StorageClass;
namespace {

/// Cone pieces a cubic span is drawn with.
constexpr int kCubicPieces = 8;

/// A value given per curve, per varying point or per vertex (or once), for width, Cs and Os:
/// its values and how they are spread.
struct CurveValues {
    enum class Spread { Constant, Uniform, Varying, Vertex } spread = Spread::Constant;
    std::vector<double> values;  // `components` numbers each
    int components = 1;
};

/// The power-basis coefficients of span j of one curve's values x (n of them, `components` each;
/// `periodic` wraps the indices), coefficient a of t^(3 - a), under basis m (row-major).
void SpanCoefficients(const double* x, size_t n, int components, const CubicBasis& basis, size_t j, bool periodic,
                      double (*c)[4]) {
    for (int comp = 0; comp < components; ++comp)
        for (int a = 0; a < 4; ++a) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) {
                size_t index = j * static_cast<size_t>(basis.step) + static_cast<size_t>(k);
                if (periodic) index %= n;
                sum += basis.m[4 * a + k] * x[index * components + comp];
            }
            c[comp][a] = sum;
        }
}

double Horner(const double* c, double t) { return ((c[0] * t + c[1]) * t + c[2]) * t + c[3]; }

/// Where a span lies in the request's arrays: its curve, that curve's vertices and first vertex
/// and varying value, its own index, and the curve's kind.
struct SpanPlace {
    size_t curve, vertices, firstVertex, firstVarying, varyingValues, span;
    bool cubic, periodic;
    const CubicBasis* basis;
};

/// Values spread as `spread` (`components` each) over one span, formed once for all the points
/// the span is sampled at: one value, the two ends of a linear interpolation, or a cubic's
/// power-basis coefficients.
class SpanValue {
  public:
    SpanValue(CurveValues::Spread spread, const double* values, int components, const SpanPlace& at)
        : m_components(components) {
        using Spread = CurveValues::Spread;
        const size_t comps = static_cast<size_t>(components);
        switch (spread) {
            case Spread::Constant:
            case Spread::Uniform:
                m_form = Form::Constant;
                if (spread == Spread::Uniform) values += at.curve * comps;
                std::copy(values, values + comps, m_ends[0]);
                return;
            case Spread::Varying:
                Linear(values, at.firstVarying + at.span, at.firstVarying + (at.span + 1) % at.varyingValues);
                return;
            case Spread::Vertex:
                if (!at.cubic) {
                    Linear(values, at.firstVertex + at.span, at.firstVertex + (at.span + 1) % at.vertices);
                    return;
                }
                m_form = Form::Cubic;
                SpanCoefficients(values + at.firstVertex * comps, at.vertices, components, *at.basis, at.span,
                                 at.periodic, m_cubic);
                return;
        }
    }

    /// The values at parameter t of the span, into out[0 .. components).
    void At(double t, double* out) const {
        for (int c = 0; c < m_components; ++c)
            out[c] = m_form == Form::Constant ? m_ends[0][c]
                     : m_form == Form::Linear ? (1 - t) * m_ends[0][c] + t * m_ends[1][c]
                                              : Horner(m_cubic[c], t);
    }

  private:
    void Linear(const double* values, size_t a, size_t b) {
        m_form = Form::Linear;
        const size_t comps = static_cast<size_t>(m_components);
        std::copy(values + a * comps, values + (a + 1) * comps, m_ends[0]);
        std::copy(values + b * comps, values + (b + 1) * comps, m_ends[1]);
    }

    enum class Form { Constant, Linear, Cubic } m_form = Form::Constant;
    int m_components;
    double m_ends[2][3] = {};
    double m_cubic[3][4] = {};
};

}  // namespace

bool RibParser::DoCurves(const RibRequest& r) {
    const std::string context = Quote(r.name);
    if (r.args.size() < 3 || r.args[0].isArray || !r.args[0].StringsP() || !r.args[1].isArray ||
        !r.args[1].NumericP() || r.args[2].isArray || !r.args[2].StringsP())
        return Fail(r.at, context +
                              " expects a type (\"linear\" or \"cubic\"), an array of vertex counts and a wrap "
                              "(\"periodic\" or \"nonperiodic\")");
    const std::string& type = r.args[0].strings[0];
    const std::string& wrap = r.args[2].strings[0];
    if (type != "linear" && type != "cubic")
        return Fail(r.args[0].at, context + " type must be \"linear\" or \"cubic\", got " + Quote(type));
    if (wrap != "periodic" && wrap != "nonperiodic")
        return Fail(r.args[2].at, context + " wrap must be \"periodic\" or \"nonperiodic\", got " + Quote(wrap));
    std::vector<RibParam> params;
    m_uniformVaries = true;  // one uniform value per curve
    const bool listed = ParamList(r, 3, &params);
    m_uniformVaries = false;
    if (!listed || !InsideWorld(r)) return false;
    const bool cubic = type == "cubic", periodic = wrap == "periodic";
    const CubicBasis& basis = m_state.vBasis;
    const size_t step = static_cast<size_t>(basis.step);

    // Each curve's vertices, spans (cubic) or segments (linear), and varying values.
    std::vector<size_t> vertices, spans;
    size_t totalVertices = 0, totalVarying = 0;
    for (double count : r.args[1].numbers) {
        if (!(count >= 1 && count == std::floor(count) && count <= 1e9))
            return Fail(r.args[1].at, context + " vertex counts must be positive integers, got " + FormatNumber(count));
        const size_t n = static_cast<size_t>(count);
        size_t s;
        if (cubic) {
            if (n < 4 || (periodic ? n % step : (n - 4) % step) != 0)
                return Fail(r.args[1].at, context + " cubic curve of " + std::to_string(n) + " vertices: with vstep " +
                                              std::to_string(step) + " a " + wrap + " curve needs " +
                                              (periodic ? "a multiple of vstep" : "4 + a multiple of vstep") +
                                              " (at least 4)");
            s = periodic ? n / step : (n - 4) / step + 1;
        } else {
            if (n < 2) return Fail(r.args[1].at, context + " linear curve of 1 vertex: a curve needs 2 or more");
            s = periodic ? n : n - 1;
        }
        vertices.push_back(n);
        spans.push_back(s);
        totalVertices += n;
        totalVarying += periodic ? s : s + 1;
    }
    if (vertices.empty()) return true;

    const RibParam* position = nullptr;
    CurveValues width, colors[2];
    width.values = {1.0};  // RI default
    colors[0].components = colors[1].components = 3;
    colors[0].values = {m_state.color.x, m_state.color.y, m_state.color.z};
    colors[1].values = {m_state.opacity.x, m_state.opacity.y, m_state.opacity.z};
    for (const RibParam& p : params) {
        const std::string& name = p.value.name;
        CurveValues* target = name == "width" || name == "constantwidth" ? &width
                              : name == "Cs"                             ? &colors[0]
                              : name == "Os"                             ? &colors[1]
                                                                         : nullptr;
        if (name == "P") {
            position = &p;
            continue;
        }
        if (!target) {
            Warn(p.at, context + " parameter " + Quote(name) + " is not supported yet; ignored");
            continue;
        }
        // The spread: the storage class of the parameter's declaration (inline or Declare'd), or
        // without one, from the count (a curve's storage classes have distinct counts but for
        // coincidences: varying and vertex on linear curves, where they mean the same, and on
        // periodic cubics of vstep 1, where the standard declaration's varying is taken).
        const size_t each = static_cast<size_t>(target->components), got = p.value.numbers.size();
        using Spread = CurveValues::Spread;
        Spread spread;
        RibDeclaration declared;
        std::string problem;
        if (name != "constantwidth" && !p.value.declaration.empty() &&
            RibDeclaration::Parse(p.value.declaration, &declared, &problem) && !declared.storage.empty()) {
            // A curve's uniform values are per curve, its vertex values per control point; it has
            // no face corners, so facevarying counts none.
            const PrimvarCounts counts{vertices.size(), totalVertices, 0, totalVarying};
            const StorageClass storage = declared.Storage();
            const size_t values = counts.Of(storage);
            if (values == 0)
                return Fail(p.at, context + " parameter " + Quote(name) + ": storage class " + Quote(declared.storage) +
                                      " is not defined on curves");
            if (!p.value.strings.empty() || got != each * values)
                return Fail(p.at, context + " parameter " + Quote(name) + " (" + p.value.declaration + ") expects " +
                                      std::to_string(each * values) + (each * values == 1 ? " number" : " numbers") +
                                      " (" + std::to_string(each) + " for each of " + std::to_string(values) + " " +
                                      declared.storage + (values == 1 ? " value" : " values") + "), got " +
                                      (p.value.strings.empty() ? std::to_string(got) : std::string("strings")));
            spread = storage == StorageClass::Constant  ? Spread::Constant
                     : storage == StorageClass::Uniform ? Spread::Uniform
                     : storage == StorageClass::Varying ? Spread::Varying
                                                        : Spread::Vertex;
        } else if (!p.value.strings.empty() || got % each != 0)
            spread = Spread::Constant, target = nullptr;
        else if (got == each)
            spread = Spread::Constant;
        else if (name != "constantwidth" && got == each * vertices.size())
            spread = Spread::Uniform;
        else if (name != "constantwidth" && got == each * totalVarying)
            spread = Spread::Varying;
        else if (name != "constantwidth" && got == each * totalVertices)
            spread = Spread::Vertex;
        else
            target = nullptr;
        if (!target)
            return Fail(p.at, context + " parameter " + Quote(name) + " expects " + std::to_string(each) +
                                  (name == "constantwidth" ? "" : ", or that per curve, varying point or vertex,") +
                                  " numbers (" + std::to_string(vertices.size()) + " curves, " +
                                  std::to_string(totalVarying) + " varying points, " + std::to_string(totalVertices) +
                                  " vertices), got " +
                                  (p.value.strings.empty() ? std::to_string(got) : std::string("strings")));
        target->spread = spread;
        target->values = p.value.numbers;
        if (name == "Os")
            for (double& v : target->values) v = std::clamp(v, 0.0, 1.0);
    }
    if (!position) return Fail(r.at, context + " needs \"P\"");
    if (!position->value.strings.empty() || position->value.numbers.size() != 3 * totalVertices)
        return Fail(position->at, context + " parameter 'P' expects " + std::to_string(3 * totalVertices) +
                                      " numbers (3 for each of " + std::to_string(totalVertices) + " vertices), got " +
                                      (position->value.strings.empty() ? std::to_string(position->value.numbers.size())
                                                                       : std::string("strings")));
    Note(r.at,
         std::string("'Curves' are drawn as tubes of their width (prman draws ribbons facing the camera)") +
             (cubic ? "; a cubic span as " + std::to_string(kCubicPieces) + " cones between points of the curve" : ""));

    // Each curve: its points along its spans at the pieces' ends, their widths and colours.
    double chordError = 0;  // the largest distance of a piece's middle from its chord's, object space
    size_t firstVertex = 0, firstVarying = 0, skipped = 0;
    for (size_t curve = 0; curve < vertices.size(); ++curve) {
        const size_t n = vertices[curve], s = spans[curve];
        const size_t varyingHere = periodic ? s : s + 1;
        const int pieces = cubic ? kCubicPieces : 1;
        for (size_t j = 0; j < s; ++j) {
            const SpanPlace place{curve, n, firstVertex, firstVarying, varyingHere, j, cubic, periodic, &basis};
            const SpanValue points(CurveValues::Spread::Vertex, position->value.numbers.data(), 3, place);
            const SpanValue widths(width.spread, width.values.data(), 1, place);
            const SpanValue colorsHere(colors[0].spread, colors[0].values.data(), 3, place);
            const SpanValue opacities(colors[1].spread, colors[1].values.data(), 3, place);
            const auto pointAt = [&](double t) {
                double p[3];
                points.At(t, p);
                return glm::dvec3(p[0], p[1], p[2]);
            };
            for (int piece = 0; piece < pieces; ++piece) {
                const double t0 = double(piece) / pieces, t1 = double(piece + 1) / pieces, tm = 0.5 * (t0 + t1);
                const glm::dvec3 a = pointAt(t0), b = pointAt(t1);
                double wa, wb, color[3], opacity[3];
                widths.At(t0, &wa);
                widths.At(t1, &wb);
                colorsHere.At(tm, color);
                opacities.At(tm, opacity);
                if (cubic) chordError = std::max(chordError, glm::length(pointAt(tm) - 0.5 * (a + b)));
                const double length = glm::length(b - a);
                if (!std::isfinite(length) || !std::isfinite(wa) || !std::isfinite(wb))
                    return Fail(r.at, context + " curve " + std::to_string(curve) + " overflows (a piece " +
                                          (std::isfinite(length) ? "width" : "length") + " beyond the doubles)");
                if (!(length > 0) || !(wa > 0 || wb > 0)) {
                    ++skipped;
                    continue;
                }
                // The cone's axis along b - a: columns e1, e2, d and the origin a.
                const glm::dvec3 d = (b - a) / length;
                const glm::dvec3 helper = std::fabs(d.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
                const glm::dvec3 e1 = glm::normalize(glm::cross(helper, d)), e2 = glm::cross(d, e1);
                const glm::dmat4 frame(glm::dvec4(e1, 0), glm::dvec4(e2, 0), glm::dvec4(d, 0), glm::dvec4(a, 1));
                Quadric cone;
                cone.kind = Quadric::Kind::Hyperboloid;
                const double end1[3] = {std::max(0.5 * wa, 0.0), 0, 0}, end2[3] = {std::max(0.5 * wb, 0.0), 0, length};
                std::copy(end1, end1 + 3, cone.point1);
                std::copy(end2, end2 + 3, cone.point2);
                cone.thetamax = 360;
                if (std::string problem = cone.Problem(); !problem.empty())
                    return Fail(r.at, context + " curve " + std::to_string(curve) + ": " + problem);
                PrimitiveDesc prim;
                prim.base = renderer::BaseSurface(renderer::PlacedQuadric{cone, m_state.ctm * frame});
                SetPrimitiveAttributes(r, &prim);
                prim.color = glm::dvec3(color[0], color[1], color[2]);
                prim.opacity = glm::clamp(glm::dvec3(opacity[0], opacity[1], opacity[2]), 0.0, 1.0);
                m_scene.primitives.push_back(std::move(prim));
            }
        }
        firstVertex += n;
        firstVarying += varyingHere;
    }
    if (chordError > 0)
        Note(r.at, "'Curves': the cones of cubic spans stray up to " + FormatNumber(chordError) +
                       " (object space) from the curve between their ends");
    if (skipped > 0)
        Warn(r.at, context + ": " + std::to_string(skipped) + " piece" + (skipped == 1 ? "" : "s") +
                       " of zero length or width drawn as nothing");
    return true;
}

}  // namespace affray::rib
