// scene/geometry/nurbs.cpp: rational patches built from control points, the spans of a
// NuPatch and the flattening of trim curves (scene/geometry/nurbs.h). Everything here runs
// once per primitive, in doubles.
#include "scene/geometry/nurbs.h"

#include "scene/geometry/pole.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace affray::renderer {

glm::dvec4 PlaceHomogeneous(const glm::dmat4& m, const glm::dvec4& p) {
    const glm::dvec3 xyz = glm::dmat3(m) * glm::dvec3(p) + glm::dvec3(m[3]) * p.w;
    return {xyz, p.w};
}

namespace {

/// The absolute values of PlaceHomogeneous's terms, for the noise floor of RationalPatch::Simplify.
glm::dvec4 PlaceSize(const glm::dmat4& m, const glm::dvec4& p) {
    glm::dmat3 linear(m);
    for (int col = 0; col < 3; ++col) linear[col] = glm::abs(linear[col]);
    const glm::dvec3 xyz = linear * glm::abs(glm::dvec3(p)) + glm::abs(glm::dvec3(m[3])) * std::fabs(p.w);
    return {xyz, std::fabs(p.w)};
}

using Poly = std::array<double, kMaxNurbsOrder>;

/// p times the linear polynomial a + b x (the degree must stay below kMaxNurbsOrder).
Poly TimesLinear(const Poly& p, double a, double b) {
    Poly out{};
    for (int m = 0; m < kMaxNurbsOrder; ++m) {
        if (p[m] == 0) continue;
        out[m] += a * p[m];
        if (m + 1 < kMaxNurbsOrder) out[m + 1] += b * p[m];
    }
    return out;
}

}  // namespace

RationalPatch RationalPatch::Bilinear(const std::array<glm::dvec4, 4>& q) {
    RationalPatch p;
    p.degreeU = p.degreeV = 1;
    // X(s,t) = q0 + (q1 - q0) s + (q2 - q0) t + (q0 - q1 - q2 + q3) s t; index (i, j) = 2 i + j.
    p.c = {q[0], q[2] - q[0], q[1] - q[0], q[0] - q[1] - q[2] + q[3]};
    const glm::dvec4 a0 = glm::abs(q[0]), a1 = glm::abs(q[1]), a2 = glm::abs(q[2]), a3 = glm::abs(q[3]);
    p.Simplify({a0, a0 + a2, a0 + a1, a0 + a1 + a2 + a3});
    return p;
}

RationalPatch RationalPatch::Bicubic(const std::array<glm::dvec4, 16>& points, const CubicBasis& uBasis,
                                     const CubicBasis& vBasis, const glm::dmat4& objectToWorld) {
    // C = Mu G Mv^T with G[a][b] the placed point of u index a, v index b (points[4 b + a]);
    // C[a][b] is the coefficient of s^(3-a) t^(3-b) (as BicubicPatch::FromControlPoints).
    std::array<glm::dvec4, 16> g, gAbs, mg{}, mgAbs{};
    for (int k = 0; k < 16; ++k) {
        g[k] = PlaceHomogeneous(objectToWorld, points[k]);
        gAbs[k] = PlaceSize(objectToWorld, points[k]);
    }
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            for (int k = 0; k < 4; ++k) {
                mg[4 * a + b] += uBasis.m[4 * a + k] * g[4 * b + k];
                mgAbs[4 * a + b] += std::fabs(uBasis.m[4 * a + k]) * gAbs[4 * b + k];
            }
    RationalPatch p;
    p.degreeU = p.degreeV = 3;
    p.c.assign(16, glm::dvec4(0.0));
    std::vector<glm::dvec4> size(16, glm::dvec4(0.0));
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            for (int k = 0; k < 4; ++k) {
                p.c[p.Index(3 - a, 3 - b)] += mg[4 * a + k] * vBasis.m[4 * b + k];
                size[p.Index(3 - a, 3 - b)] += mgAbs[4 * a + k] * std::fabs(vBasis.m[4 * b + k]);
            }
    p.Simplify(size);
    return p;
}

void RationalPatch::Simplify(const std::vector<glm::dvec4>& size) {
    // A coefficient that cancels in exact arithmetic keeps rounding noise of a few ulps of the
    // terms summed: zeroed, so that the evaluation skips it (the surface moves by < 1e-14 of them).
    for (size_t k = 0; k < c.size(); ++k)
        for (int i = 0; i < 4; ++i)
            if (std::fabs(c[k][i]) <= 1e-14 * size[k][i]) c[k][i] = 0;
    bool constantW = true;
    for (size_t k = 1; k < c.size(); ++k) constantW = constantW && c[k].w == 0;
    rational = !constantW || c[0].w != 1;
    if (constantW && c[0].w != 0) {
        // W is a constant w0: P = X / w0 is a polynomial.
        const double w0 = c[0].w;
        for (glm::dvec4& x : c) x = glm::dvec4(glm::dvec3(x) / w0, 0.0);
        c[0].w = 1;
        if (hasST && stHomogeneous)
            for (glm::dvec2& x : st) x /= w0;
        stHomogeneous = false;
        rational = false;
    }
    poles = FindPatchPoles(*this);
}

glm::dvec3 RationalPatch::At(double s, double t) const {
    const SurfaceFrame<double> f = RationalFrame<double>(*this, s, t);
    return {f.P.x, f.P.y, f.P.z};
}

bool RationalPatch::FiniteP() const {
    for (const glm::dvec4& x : c)
        for (int i = 0; i < 4; ++i)
            if (!std::isfinite(x[i])) return false;
    return true;
}

std::string ToString(const RationalPatch& p) {
    std::ostringstream out;
    out << (p.rational ? "rational " : "polynomial ") << p.degreeU << 'x' << p.degreeV << " [";
    for (size_t k = 0; k < p.c.size(); ++k)
        out << (k ? " " : "") << '[' << p.c[k].x << ' ' << p.c[k].y << ' ' << p.c[k].z << ' ' << p.c[k].w << ']';
    out << ']';
    if (p.hasST) out << " st";
    return out.str();
}

std::string KnotVector::Problem(const std::string& name) const {
    std::ostringstream out;
    if (order < 2 || order > kMaxNurbsOrder) {
        out << "the " << name << " order must be 2 to " << kMaxNurbsOrder << " (degree 1 to " << kMaxNurbsOrder - 1
            << "), got " << order;
    } else if (n < order) {
        out << "the " << name << " direction has " << n << " control points, fewer than its order " << order;
    } else if (knots.size() != static_cast<size_t>(n) + static_cast<size_t>(order)) {
        out << "the " << name << " knot vector needs n + order = " << n + order << " knots, got " << knots.size();
    } else {
        for (size_t i = 0; i < knots.size(); ++i) {
            if (!std::isfinite(knots[i])) {
                out << "the " << name << " knot " << i << " is not finite";
                return out.str();
            }
            if (i > 0 && knots[i] < knots[i - 1]) {
                out << "the " << name << " knot vector decreases at knot " << i << " (" << knots[i - 1] << " then "
                    << knots[i] << ")";
                return out.str();
            }
        }
        const double lo = knots[order - 1], hi = knots[n];
        if (!(lo < hi))
            out << "the " << name << " knot vector has an empty parameter range (knots " << order - 1 << " and " << n
                << " are both " << lo << ")";
        else if (!(min < max) || min < lo || max > hi)
            out << "the " << name << " range " << name << "min " << min << ", " << name << "max " << max
                << " must be increasing and within the knots' parameter range [" << lo << ", " << hi << "]";
    }
    return out.str();
}

std::vector<KnotVector::Span> KnotVector::Spans() const {
    std::vector<Span> out;
    for (int k = order - 1; k < n; ++k) {
        if (!(knots[k] < knots[k + 1])) continue;
        const double lo = std::max(knots[k], min), hi = std::min(knots[k + 1], max);
        if (lo < hi) out.push_back({k, lo, hi});
    }
    return out;
}

std::vector<std::array<double, kMaxNurbsOrder>> KnotVector::SpanBasis(const Span& span) const {
    // Cox-de Boor on polynomials of x (u = lo + h x): N_{i,1} = 1 for i = k only, and
    //   N_{i,q} = (u - t_i) / (t_{i+q-1} - t_i) N_{i,q-1} + (t_{i+q} - u) / (t_{i+q} - t_{i+1}) N_{i+1,q-1}
    // (a term with a zero denominator is 0). Local index l stands for N_{k-order+1+l}.
    const int k = span.k;
    const double h = span.hi - span.lo;
    std::vector<Poly> basis(order, Poly{});
    basis[order - 1][0] = 1;
    for (int q = 2; q <= order; ++q) {
        std::vector<Poly> next(order, Poly{});
        for (int l = order - q; l < order; ++l) {
            const int i = k - order + 1 + l;
            const double left = knots[i + q - 1] - knots[i], right = knots[i + q] - knots[i + 1];
            Poly sum{};
            if (left > 0) {
                const Poly a = TimesLinear(basis[l], (span.lo - knots[i]) / left, h / left);
                for (int m = 0; m < kMaxNurbsOrder; ++m) sum[m] += a[m];
            }
            if (right > 0 && l + 1 < order) {
                const Poly b = TimesLinear(basis[l + 1], (knots[i + q] - span.lo) / right, -h / right);
                for (int m = 0; m < kMaxNurbsOrder; ++m) sum[m] += b[m];
            }
            next[l] = sum;
        }
        basis = std::move(next);
    }
    return basis;
}

namespace {

using SpanBasisPolys = std::vector<std::array<double, kMaxNurbsOrder>>;

/// The coefficients (RationalPatch's layout) over the span (su, sv) of a variable of `storage`
/// with one value V per entry: vertex values times each point's w (`world`, the homogeneous
/// points) times their basis polynomials `bu`, `bv`; varying ones bilinear across the whole
/// segment between its corner values; a uniform or constant one the constant term.
template <class V>
std::vector<V> SpanValues(const KnotVector& ku, const KnotVector& kv, const KnotVector::Span& su,
                          const KnotVector::Span& sv, const SpanBasisPolys& bu, const SpanBasisPolys& bv,
                          const std::vector<glm::dvec4>& world, StorageClass storage, const std::vector<V>& values) {
    auto index = [&](int i, int j) { return static_cast<size_t>(kv.order) * static_cast<size_t>(i) + size_t(j); };
    std::vector<V> out(static_cast<size_t>(ku.order) * static_cast<size_t>(kv.order), V(0.0));
    const int segU = su.k - ku.order + 1, segV = sv.k - kv.order + 1;
    if (storage == StorageClass::Vertex) {
        for (int b = 0; b < kv.order; ++b)
            for (int a = 0; a < ku.order; ++a) {
                const size_t point = static_cast<size_t>(sv.k - kv.order + 1 + b) * static_cast<size_t>(ku.n) +
                                     static_cast<size_t>(su.k - ku.order + 1 + a);
                for (int i = 0; i < ku.order; ++i)
                    for (int j = 0; j < kv.order; ++j) {
                        const double weight = bu[a][i] * bv[b][j];
                        if (weight != 0) out[index(i, j)] += weight * world[point].w * values[point];
                    }
            }
    } else if (storage == StorageClass::Varying) {
        // Along u the corner weights 1 - f and f, f = (u - t_k) / (t_k+1 - t_k) affine in the
        // span's x.
        auto weights = [](const KnotVector& kn, const KnotVector::Span& s, double w[2][2]) {
            const double t0 = kn.knots[s.k], len = kn.knots[s.k + 1] - t0;
            const double f0 = (s.lo - t0) / len, f1 = (s.hi - t0) / len;
            w[0][0] = 1 - f0, w[0][1] = -(f1 - f0), w[1][0] = f0, w[1][1] = f1 - f0;
        };
        double wu[2][2], wv[2][2];
        weights(ku, su, wu);
        weights(kv, sv, wv);
        const int across = ku.n - ku.order + 2;
        for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) {
                const V value =
                    values[static_cast<size_t>(segV + b) * static_cast<size_t>(across) + static_cast<size_t>(segU + a)];
                for (int i = 0; i < 2; ++i)
                    for (int j = 0; j < 2; ++j) out[index(i, j)] += wu[a][i] * wv[b][j] * value;
            }
    } else if (storage == StorageClass::Uniform) {
        const int across = ku.n - ku.order + 1;
        out[0] = values[static_cast<size_t>(segV) * static_cast<size_t>(across) + static_cast<size_t>(segU)];
    } else {
        out[0] = values[0];
    }
    return out;
}

}  // namespace

std::vector<NurbsSpan> SplitNurbs(const NurbsSurface& surface, const glm::dmat4& objectToWorld) {
    const KnotVector &ku = surface.u, &kv = surface.v;
    // Equal weights w0 (every "P" NuPatch): sum N = 1 makes the surface the polynomial sum N Pw / w0,
    // so W is set to 1 exactly rather than summed from basis polynomials that only cancel to
    // rounding (their noise grows with the degree).
    const bool polynomial = std::all_of(surface.points.begin(), surface.points.end(),
                                        [&](const glm::dvec4& p) { return p.w == surface.points[0].w; });
    std::vector<glm::dvec4> world(surface.points.size()), size(surface.points.size());
    for (size_t i = 0; i < world.size(); ++i) {
        const glm::dvec4 p =
            polynomial ? glm::dvec4(glm::dvec3(surface.points[i]) / surface.points[i].w, 1.0) : surface.points[i];
        world[i] = PlaceHomogeneous(objectToWorld, p);
        size[i] = PlaceSize(objectToWorld, p);
    }
    const std::vector<KnotVector::Span> spansU = ku.Spans(), spansV = kv.Spans();
    std::vector<NurbsSpan> out;
    for (const KnotVector::Span& sv : spansV) {
        const auto bv = kv.SpanBasis(sv);
        for (const KnotVector::Span& su : spansU) {
            const auto bu = ku.SpanBasis(su);
            NurbsSpan span;
            RationalPatch& p = span.patch;
            p.degreeU = ku.order - 1;
            p.degreeV = kv.order - 1;
            const size_t count = static_cast<size_t>(ku.order) * static_cast<size_t>(kv.order);
            p.c.assign(count, glm::dvec4(0.0));
            std::vector<glm::dvec4> sizes(count, glm::dvec4(0.0));
            // The control points of the span, each times its two basis polynomials.
            for (int b = 0; b < kv.order; ++b)
                for (int a = 0; a < ku.order; ++a) {
                    const size_t index = static_cast<size_t>(sv.k - kv.order + 1 + b) * static_cast<size_t>(ku.n) +
                                         static_cast<size_t>(su.k - ku.order + 1 + a);
                    for (int i = 0; i < ku.order; ++i)
                        for (int j = 0; j < kv.order; ++j) {
                            const double weight = bu[a][i] * bv[b][j];
                            if (weight == 0) continue;
                            p.c[p.Index(i, j)] += weight * world[index];
                            sizes[p.Index(i, j)] += std::fabs(weight) * size[index];
                        }
                }
            if (const NurbsST* st = surface.st ? &*surface.st : nullptr) {
                p.hasST = true;
                p.stHomogeneous = st->storage == StorageClass::Vertex;
                p.st = SpanValues(ku, kv, su, sv, bu, bv, world, st->storage, st->values);
            }
            // Colours: vertex ones divided by W as P is (no W when it is 1: equal weights).
            auto colorField = [&](const NurbsColor& color) {
                ColorField f;
                f.degreeU = p.degreeU;
                f.degreeV = p.degreeV;
                f.c = SpanValues(ku, kv, su, sv, bu, bv, world, color.storage, color.values);
                if (color.storage == StorageClass::Vertex && !polynomial)
                    for (const glm::dvec4& x : p.c) f.w.push_back(x.w);
                return f;
            };
            if (surface.Cs) span.Cs = colorField(*surface.Cs);
            if (surface.Os) span.Os = colorField(*surface.Os);
            if (polynomial)
                for (size_t i = 0; i < count; ++i) p.c[i].w = i == 0 ? 1.0 : 0.0, sizes[i].w = 0;
            p.Simplify(sizes);
            span.range = ParameterRange{su.lo, su.hi, sv.lo, sv.hi};
            out.push_back(std::move(span));
        }
    }
    return out;
}

bool TrimCurves::KeptP(double u, double v) const {
    // Even-odd rule: the crossings of the ray from (u, v) towards +u with every loop's segments.
    bool inside = false;
    for (const std::vector<glm::dvec2>& loop : loops) {
        const size_t n = loop.size();
        for (size_t i = 0; i < n; ++i) {
            const glm::dvec2 a = loop[i], b = loop[(i + 1) % n];
            if ((a.y > v) != (b.y > v) && u < a.x + (v - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
        }
    }
    return inside == keepInside;
}

bool TrimCurves::RemovedP(double u0, double u1, double v0, double v1) const {
    // No segment's box meets the rectangle: no loop enters it, so it lies on one side of them all.
    for (const std::vector<glm::dvec2>& loop : loops) {
        const size_t n = loop.size();
        for (size_t i = 0; i < n; ++i) {
            const glm::dvec2 a = loop[i], b = loop[(i + 1) % n];
            if (std::max(a.x, b.x) >= u0 && std::min(a.x, b.x) <= u1 && std::max(a.y, b.y) >= v0 &&
                std::min(a.y, b.y) <= v1)
                return false;
        }
    }
    return !KeptP(0.5 * (u0 + u1), 0.5 * (v0 + v1));
}

void FlattenTrimCurve(const KnotVector& k, const std::vector<glm::dvec3>& uvw, double tolerance,
                      std::vector<glm::dvec2>* loop) {
    for (const KnotVector::Span& span : k.Spans()) {
        const auto basis = k.SpanBasis(span);
        // The homogeneous curve of the span as polynomials in x.
        std::array<glm::dvec3, kMaxNurbsOrder> c{};
        for (int a = 0; a < k.order; ++a)
            for (int m = 0; m < k.order; ++m)
                c[m] += basis[a][m] * uvw[static_cast<size_t>(span.k - k.order + 1) + static_cast<size_t>(a)];
        auto at = [&](double x) {
            glm::dvec3 h = c[k.order - 1];
            for (int m = k.order - 2; m >= 0; --m) h = h * x + c[m];
            return glm::dvec2(h.x / h.z, h.y / h.z);
        };
        // Each segment of the uniform sampling halved while its midpoint strays from its chord.
        auto refine = [&](auto&& self, double x0, glm::dvec2 p0, double x1, glm::dvec2 p1, int depth) -> void {
            const double xm = 0.5 * (x0 + x1);
            const glm::dvec2 pm = at(xm), chord = p1 - p0;
            const double length = glm::length(chord);
            const double away = length > 0 ? std::fabs(chord.x * (pm.y - p0.y) - chord.y * (pm.x - p0.x)) / length
                                           : glm::length(pm - p0);
            if (away > tolerance && depth < 12) {
                self(self, x0, p0, xm, pm, depth + 1);
                self(self, xm, pm, x1, p1, depth + 1);
                return;
            }
            loop->push_back(p1);
        };
        const int samples = 16 * k.order;
        glm::dvec2 previous = at(0);
        if (loop->empty() || loop->back() != previous) loop->push_back(previous);
        for (int i = 1; i <= samples; ++i) {
            const double x = double(i) / samples;
            const glm::dvec2 p = at(x);
            refine(refine, double(i - 1) / samples, previous, x, p, 0);
            previous = p;
        }
    }
}

}  // namespace affray::renderer
