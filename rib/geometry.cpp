// rib/geometry.cpp: RIB requests that place geometry: Patch, PatchMesh (rational with "Pw"), the quadrics (Sphere,
// Cylinder, Cone, Disk, Torus, Hyperboloid, Paraboloid) and CoordinateSystem. Rules shared with
// rib.cpp are in rib_parser.h. Every primitive takes the graphics state current at its request;
// its orientation is resolved here into BaseSurface::flipNormal, since the camera transform it
// depends on is known once geometry is allowed (inside the world block).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "rib/parser.h"

namespace affray::rib {

using renderer::StorageClass;

// flipNormal = (det objectToWorld < 0) XOR insideOut, as documented in scene.h: the first term
// undoes the turn a mirroring placement gives dPdu x dPdv, the second applies the RI rule.
bool RibParser::FlipNormalP() const {
    const bool mirrored = glm::determinant(glm::dmat3(m_state.ctm)) < 0;
    return mirrored != m_state.insideOut;
}

void RibParser::SetPrimitiveAttributes(const RibRequest& r, PrimitiveDesc* p) const {
    p->color = m_state.color;
    p->opacity = m_state.opacity;
    p->base.flipNormal = FlipNormalP();
    p->base.textureCoordinates = m_state.textureCoordinates;
    // Made once per request: the primitives of one request (a mesh's pieces) share them.
    if (m_attributesSerial != m_requestSerial || !m_attributes) {
        auto a = std::make_shared<renderer::PrimitiveAttributes>();
        a->transmission = m_state.transmission;
        a->cameraVisible = m_state.cameraVisible;
        a->sceneTolerance = std::max(0.5 * std::sqrt(m_state.shadingRate), m_state.flatness);
        a->surface = m_state.surface;
        a->displacement = m_state.displacement;
        a->atmosphere = m_state.atmosphere;
        a->line = r.at.line;
        a->column = r.at.column;
        a->objectToWorld = m_state.ctm;
        a->motion = m_state.motion;
        a->twoSided = m_state.twoSided;
        a->lights = m_state.lights;
        a->scopedSpaces = m_state.scopedSpaces;
        m_attributes = std::move(a);
        m_attributesSerial = m_requestSerial;
    }
    p->attributes = m_attributes;
}

bool RibParser::PatchPoints(const RibRequest& r, const std::vector<RibParam>& params, const std::string& context,
                            size_t count, bool heights, std::vector<glm::dvec4>* out, bool* rational) {
    out->assign(count, glm::dvec4(0, 0, 0, 1));
    *rational = false;
    std::vector<double> v;
    bool havePosition = false;
    for (const RibParam& p : params) {
        const std::string& n = p.value.name;
        if (n == "P") {
            v.resize(3 * count);
            if (!ParamNumbers(p, context, 3 * count, v.data())) return false;
            for (size_t i = 0; i < count; ++i) (*out)[i] = glm::dvec4(v[3 * i], v[3 * i + 1], v[3 * i + 2], 1.0);
        } else if (n == "Pw") {  // homogeneous points (x w, y w, z w, w): a rational patch
            v.resize(4 * count);
            if (!ParamNumbers(p, context, 4 * count, v.data())) return false;
            for (size_t i = 0; i < count; ++i) {
                const double w = v[4 * i + 3];
                // The patch divides by the weighted sum of the w; positive weights keep it > 0.
                if (!(w > 0) || !std::isfinite(w))
                    return Fail(p.at, context + " parameter 'Pw': point " + std::to_string(i) + " has w = " +
                                          FormatNumber(w) + "; the weights of a rational patch must be positive");
                (*out)[i] = glm::dvec4(v[4 * i], v[4 * i + 1], v[4 * i + 2], w);
                *rational = *rational || w != 1;
            }
        } else if (n == "Pz" && heights) {  // heights over the unit square (x = u, y = v)
            v.resize(count);
            if (!ParamNumbers(p, context, count, v.data())) return false;
            for (size_t i = 0; i < count; ++i) (*out)[i] = glm::dvec4(double(i & 1), double(i >> 1), v[i], 1.0);
        } else if (n == "Pz") {
            return Fail(p.at, context + " parameter 'Pz' is supported on 'Patch \"bilinear\"' only; give \"P\"");
        } else if (n == "Cs" || n == "Os") {
            continue;  // PatchColors reads them
        } else {
            Warn(p.at, context + " parameter " + Quote(n) + " is not supported yet; ignored");
            continue;
        }
        havePosition = true;
    }
    if (!havePosition) return Fail(r.at, context + " needs a \"P\" parameter");
    return true;
}

bool RibParser::AddBilinear(const RibRequest& r, const std::string& context, const std::array<glm::dvec3, 4>& corners,
                            const renderer::ParameterRange& range) {
    renderer::BilinearPatch world;
    for (int i = 0; i < 4; ++i) {
        world.corners[i] = TransformPoint(m_state.ctm, corners[i]);
        if (!FiniteP(world.corners[i]))
            return Fail(r.at, context + " corner " + std::to_string(i) + " overflows in world space");
    }
    PrimitiveDesc patch;
    patch.base = renderer::BaseSurface(world, false, range);
    SetPrimitiveAttributes(r, &patch);
    m_scene.primitives.push_back(std::move(patch));
    return true;
}

bool RibParser::AddBicubic(const RibRequest& r, const std::string& context, const std::array<glm::dvec3, 16>& points,
                           const renderer::ParameterRange& range) {
    const renderer::BicubicPatch bicubic =
        renderer::BicubicPatch::FromControlPoints(points, m_state.uBasis, m_state.vBasis, m_state.ctm);
    if (!bicubic.FiniteP()) return Fail(r.at, context + " overflows in world space");
    PrimitiveDesc patch;
    patch.base = renderer::BaseSurface(bicubic, false, range);
    SetPrimitiveAttributes(r, &patch);
    m_scene.primitives.push_back(std::move(patch));
    return true;
}

bool RibParser::DoPatch(const RibRequest& r) {
    std::string type;
    if (!LeadingString(r, "a patch type", &type)) return false;
    if (type != "bilinear" && type != "bicubic")
        return Fail(r.args[0].at, "unknown patch type " + Quote(type) + " (expected \"bilinear\" or \"bicubic\")");
    std::vector<RibParam> params;
    if (!ParamList(r, 1, &params) || !InsideWorld(r)) return false;

    const bool bicubic = type == "bicubic";
    const std::string context = "'Patch \"" + type + "\"'";
    std::vector<glm::dvec4> points;
    bool rational;
    if (!PatchPoints(r, params, context, bicubic ? 16 : 4, !bicubic, &points, &rational)) return false;
    std::optional<ColorValues> colors[2];
    const size_t nPoints = bicubic ? 16 : 4;
    if (!PatchColors(params, context, {1, nPoints, 4, 4}, colors)) return false;
    if (!AddPatch(r, context, bicubic, rational, points, {})) return false;
    std::vector<size_t> vertices(nPoints);
    for (size_t i = 0; i < nPoints; ++i) vertices[i] = i;
    PatchColorFields(&m_scene.primitives.back(), colors, 0, {0, 1, 2, 3}, vertices, points, bicubic, rational);
    return true;
}

bool RibParser::PatchColors(const std::vector<RibParam>& params, const std::string& context,
                            const PrimvarCounts& counts, std::optional<ColorValues> (&colors)[2]) {
    for (const RibParam& p : params)
        if (p.value.name == "Cs" || p.value.name == "Os") {
            ColorValues c;
            if (!ColorPrimvar(p, context, counts, true, &c)) return false;
            colors[p.value.name == "Os"] = std::move(c);
        }
    return true;
}

// Per storage class: constant and uniform values are the patch's colour; varying and
// facevarying ones bilinear between the patch's corners; vertex ones in the patch's own basis
// (bilinear, or the current bicubic Basis), weighted by the points' w and divided by their
// weighted sum on a rational patch, as P is.
void RibParser::PatchColorFields(PrimitiveDesc* prim, const std::optional<ColorValues> (&colors)[2], size_t face,
                                 const std::array<size_t, 4>& corners, const std::vector<size_t>& vertices,
                                 const std::vector<glm::dvec4>& points, bool bicubic, bool rational) {
    using renderer::ColorField;
    for (int k = 0; k < 2; ++k) {
        if (!colors[k]) continue;
        const std::vector<glm::dvec3>& values = colors[k]->values;
        ColorField field;
        switch (colors[k]->storage) {
            case StorageClass::Constant: field.c = {values[0]}; break;
            case StorageClass::Uniform: field.c = {values[face]}; break;
            case StorageClass::Varying:
            case StorageClass::FaceVarying:
                field = ColorField::Bilinear(
                    {values[corners[0]], values[corners[1]], values[corners[2]], values[corners[3]]});
                break;
            case StorageClass::Vertex: {
                // The control values, times w on a rational patch (W from the w alone).
                auto w = [&](size_t i) { return rational ? points[vertices[i]].w : 1.0; };
                if (!bicubic) {
                    field = ColorField::Bilinear({values[vertices[0]] * w(0), values[vertices[1]] * w(1),
                                                  values[vertices[2]] * w(2), values[vertices[3]] * w(3)});
                    if (rational)
                        for (const glm::dvec3& x : ColorField::Bilinear({glm::dvec3(w(0)), glm::dvec3(w(1)),
                                                                         glm::dvec3(w(2)), glm::dvec3(w(3))})
                                                       .c)
                            field.w.push_back(x.x);
                    break;
                }
                std::array<glm::dvec3, 16> g, weights;
                for (size_t i = 0; i < 16; ++i) g[i] = values[vertices[i]] * w(i), weights[i] = glm::dvec3(w(i));
                const renderer::BicubicPatch cubic =
                    renderer::BicubicPatch::FromControlPoints(g, m_state.uBasis, m_state.vBasis, glm::dmat4(1.0));
                field.degreeU = field.degreeV = 3;
                field.c.assign(cubic.c.begin(), cubic.c.end());
                if (rational)
                    for (const glm::dvec3& x : renderer::BicubicPatch::FromControlPoints(
                                                   weights, m_state.uBasis, m_state.vBasis, glm::dmat4(1.0))
                                                   .c)
                        field.w.push_back(x.x);
                break;
            }
        }
        prim->SetColor(k, std::move(field));
    }
}

// A patch of homogeneous control points: on the bilinear or bicubic fast path when every w is 1,
// else a rational patch (scene/geometry/nurbs.h).
bool RibParser::AddPatch(const RibRequest& r, const std::string& context, bool bicubic, bool rational,
                         const std::vector<glm::dvec4>& points, const renderer::ParameterRange& range) {
    auto point = [&](size_t i) { return glm::dvec3(points[i]); };
    if (bicubic) {
        std::array<glm::dvec4, 16> g;
        std::copy(points.begin(), points.end(), g.begin());
        if (rational)
            return AddRational(r, context,
                               renderer::RationalPatch::Bicubic(g, m_state.uBasis, m_state.vBasis, m_state.ctm), range,
                               nullptr);
        std::array<glm::dvec3, 16> p;
        for (size_t i = 0; i < 16; ++i) p[i] = point(i);
        return AddBicubic(r, context, p, range);
    }
    if (rational) {
        std::array<glm::dvec4, 4> corners;
        for (size_t i = 0; i < 4; ++i) corners[i] = renderer::PlaceHomogeneous(m_state.ctm, points[i]);
        return AddRational(r, context, renderer::RationalPatch::Bilinear(corners), range, nullptr);
    }
    return AddBilinear(r, context, {point(0), point(1), point(2), point(3)}, range);
}

// PatchMesh type nu uwrap nv vwrap ...: nu x nv control points (u fastest) cut into patches as
// RI 3.2 section 5.2 says. Per direction, with n points and wrap mode periodic or not:
//   bilinear: n - 1 patches (n if periodic), patch i on points i, i + 1;
//   bicubic:  (n - 4) / step + 1 patches (n / step if periodic), patch i on points i * step + 0..3;
// indices taken modulo n when periodic (the first points repeat). Patch i of m covers the mesh's
// u from i / m to (i + 1) / m: u and v span the whole mesh.
bool RibParser::DoPatchMesh(const RibRequest& r) {
    std::string type;
    if (!LeadingString(r, "a patch type", &type)) return false;
    if (type != "bilinear" && type != "bicubic")
        return Fail(r.args[0].at, "unknown patch type " + Quote(type) + " (expected \"bilinear\" or \"bicubic\")");
    const bool bicubic = type == "bicubic";
    const std::string context = "'PatchMesh \"" + type + "\"'";
    if (r.args.size() < 5)
        return Fail(r.at, context + " expects nu uwrap nv vwrap after the type, got " +
                              std::to_string(r.args.size() - 1) + " arguments");
    int n[2], patches[2], step[2] = {1, 1};
    bool periodic[2];
    if (bicubic) step[0] = m_state.uBasis.step, step[1] = m_state.vBasis.step;
    for (int axis = 0; axis < 2; ++axis) {
        const RibArg& count = r.args[1 + 2 * axis];
        const RibArg& wrap = r.args[2 + 2 * axis];
        const std::string name = axis == 0 ? "nu" : "nv", wrapName = axis == 0 ? "uwrap" : "vwrap";
        if (count.isArray || !count.NumericP() || count.numbers.size() != 1 || !(count.numbers[0] >= 1) ||
            count.numbers[0] != std::floor(count.numbers[0]) || count.numbers[0] > 1e6)
            return Fail(count.at, context + ": " + name + " must be a positive integer, got " + count.Describe());
        if (wrap.isArray || !wrap.StringsP() || (wrap.strings[0] != "periodic" && wrap.strings[0] != "nonperiodic"))
            return Fail(wrap.at,
                        context + ": " + wrapName + " must be \"periodic\" or \"nonperiodic\", got " + wrap.Describe());
        n[axis] = static_cast<int>(count.numbers[0]);
        periodic[axis] = wrap.strings[0] == "periodic";
        // The number of patches, and what the count must satisfy for it to be whole.
        const std::string stepText = std::to_string(step[axis]);
        if (!bicubic) {
            if (n[axis] < 2) return Fail(count.at, context + ": " + name + " must be at least 2");
            patches[axis] = periodic[axis] ? n[axis] : n[axis] - 1;
        } else if (periodic[axis]) {
            if (n[axis] % step[axis] != 0)
                return Fail(count.at, context + ": a periodic mesh needs " + name + " a multiple of the " +
                                          (axis == 0 ? "u" : "v") + " step " + stepText + ", got " +
                                          std::to_string(n[axis]));
            patches[axis] = n[axis] / step[axis];
        } else {
            if (n[axis] < 4 || (n[axis] - 4) % step[axis] != 0)
                return Fail(count.at, context + ": a nonperiodic mesh needs " + name + " = 4 + k * " + stepText +
                                          " (the " + (axis == 0 ? "u" : "v") + " step), got " +
                                          std::to_string(n[axis]));
            patches[axis] = (n[axis] - 4) / step[axis] + 1;
        }
    }
    std::vector<RibParam> params;
    m_uniformVaries = true;  // one uniform value per patch
    const bool listed = ParamList(r, 5, &params);
    m_uniformVaries = false;
    if (!listed || !InsideWorld(r)) return false;
    std::vector<glm::dvec4> points;
    bool rational;
    if (!PatchPoints(r, params, context, size_t(n[0]) * size_t(n[1]), false, &points, &rational)) return false;
    // Varying values lie at the patches' corners: one more than the patches across a
    // nonperiodic direction.
    const size_t varyingU = size_t(patches[0]) + (periodic[0] ? 0 : 1);
    const size_t varyingV = size_t(patches[1]) + (periodic[1] ? 0 : 1);
    std::optional<ColorValues> colors[2];
    if (!PatchColors(params, context,
                     {size_t(patches[0]) * size_t(patches[1]), points.size(), varyingU * varyingV, varyingU * varyingV},
                     colors))
        return false;

    auto pointIndex = [&](int i, int j) {
        // Periodic indices wrap; nonperiodic ones stay in range by the counts checked above.
        return size_t(j % n[1]) * size_t(n[0]) + size_t(i % n[0]);
    };
    auto varying = [&](int i, int j) { return (size_t(j) % varyingV) * varyingU + size_t(i) % varyingU; };
    for (int pv = 0; pv < patches[1]; ++pv)
        for (int pu = 0; pu < patches[0]; ++pu) {
            const renderer::ParameterRange range{double(pu) / patches[0], double(pu + 1) / patches[0],
                                                 double(pv) / patches[1], double(pv + 1) / patches[1]};
            std::vector<size_t> vertices;
            if (bicubic) {
                for (int b = 0; b < 4; ++b)
                    for (int a = 0; a < 4; ++a) vertices.push_back(pointIndex(pu * step[0] + a, pv * step[1] + b));
            } else {
                vertices = {pointIndex(pu, pv), pointIndex(pu + 1, pv), pointIndex(pu, pv + 1),
                            pointIndex(pu + 1, pv + 1)};
            }
            std::vector<glm::dvec4> g(vertices.size());
            for (size_t i = 0; i < vertices.size(); ++i) g[i] = points[vertices[i]];
            if (!AddPatch(r, context, bicubic, rational, g, range)) return false;
            PatchColorFields(&m_scene.primitives.back(), colors, size_t(pv) * size_t(patches[0]) + size_t(pu),
                             {varying(pu, pv), varying(pu + 1, pv), varying(pu, pv + 1), varying(pu + 1, pv + 1)},
                             vertices, points, bicubic, rational);
        }
    return true;
}

namespace {

/// The positional arguments of each quadric request (RI 3.2 section 5.2), in order.
const char* QuadricArgNames(Quadric::Kind kind) {
    switch (kind) {
        case Quadric::Kind::Sphere:
        case Quadric::Kind::Cylinder: return "radius zmin zmax thetamax";
        case Quadric::Kind::Cone:
        case Quadric::Kind::Disk: return "height radius thetamax";
        case Quadric::Kind::Torus: return "rmajor rminor phimin phimax thetamax";
        case Quadric::Kind::Hyperboloid: return "x1 y1 z1 x2 y2 z2 thetamax";
        case Quadric::Kind::Paraboloid: return "rmax zmin zmax thetamax";
    }
    return "";
}

/// The quadric with the request's arguments `v` (as many as QuadricArgNames lists).
Quadric MakeQuadric(Quadric::Kind kind, const double* v) {
    Quadric q;
    q.kind = kind;
    switch (kind) {
        case Quadric::Kind::Sphere:
        case Quadric::Kind::Cylinder:
        case Quadric::Kind::Paraboloid: q.radius = v[0], q.zmin = v[1], q.zmax = v[2], q.thetamax = v[3]; break;
        case Quadric::Kind::Cone:
        case Quadric::Kind::Disk: q.height = v[0], q.radius = v[1], q.thetamax = v[2]; break;
        case Quadric::Kind::Torus:
            q.majorRadius = v[0], q.minorRadius = v[1], q.phimin = v[2], q.phimax = v[3];
            q.thetamax = v[4];
            break;
        case Quadric::Kind::Hyperboloid:
            for (int i = 0; i < 3; ++i) q.point1[i] = v[i], q.point2[i] = v[3 + i];
            q.thetamax = v[6];
            break;
    }
    return q;
}

/// Why the surface of `q` is empty, or "" if it is not. Exports write such quadrics (a sweep
/// animated from 0 degrees, an object scaled to nothing); prman draws nothing for them.
std::string EmptyReason(const Quadric& q) {
    using Kind = Quadric::Kind;
    if (q.thetamax == 0) return "thetamax is 0";
    const bool radial = q.kind != Kind::Torus && q.kind != Kind::Hyperboloid;
    if (radial && q.radius < 0) return "";  // an error (Quadric::Problem), not an empty surface
    if (radial && q.radius == 0) return q.kind == Kind::Paraboloid ? "rmax is 0" : "the radius is 0";
    switch (q.kind) {
        case Kind::Sphere:
            // A reversed range (zmin > zmax) is no sphere's: Quadric::Problem refuses it.
            if (q.zmin == q.zmax || (q.zmin < q.zmax && (q.zmin >= q.radius || q.zmax <= -q.radius)))
                return "zmin..zmax does not cut the sphere";
            break;
        case Kind::Cylinder:
        case Kind::Paraboloid:
            if (q.zmin == q.zmax) return "zmin equals zmax";
            break;
        case Kind::Torus:
            if (q.minorRadius < 0) return "";
            if (q.minorRadius == 0) return "the minor radius is 0";
            if (q.phimin == q.phimax) return "phimin equals phimax";
            break;
        case Kind::Hyperboloid:
            if (std::equal(q.point1, q.point1 + 3, q.point2)) return "point1 equals point2";
            break;
        case Kind::Cone:
        case Kind::Disk: break;
    }
    return "";
}

}  // namespace

bool RibParser::DoQuadric(const RibRequest& r, Quadric::Kind kind) {
    const char* names = QuadricArgNames(kind);
    const size_t count = 1 + std::count(names, names + std::strlen(names), ' ');
    double v[7];
    size_t next = 0;
    std::vector<RibParam> params;
    if (!LeadingNumbers(r, count, names, v, &next) || !ParamList(r, next, &params) || !InsideWorld(r)) return false;
    // Cs and Os: constant or uniform (one value), or four at the corners of (u,v) (varying,
    // vertex, facevarying), bilinear between them. Other variables are not used yet.
    std::optional<ColorValues> colors[2];
    for (const RibParam& p : params) {
        if (p.value.name != "Cs" && p.value.name != "Os") {
            Warn(p.at, Quote(r.name) + " parameter " + Quote(p.value.name) + " is not supported yet; ignored");
            continue;
        }
        ColorValues c;
        if (!ColorPrimvar(p, Quote(r.name), {1, 4, 4, 4}, true, &c)) return false;
        colors[p.value.name == "Os"] = std::move(c);
    }

    const Quadric quadric = MakeQuadric(kind, v);
    if (const std::string empty = EmptyReason(quadric); !empty.empty()) {
        Warn(r.at, Quote(r.name) + " " + empty + ": the surface is empty; skipped");
        return true;
    }
    if (std::string problem = quadric.Problem(); !problem.empty()) return Fail(r.at, Quote(r.name) + " " + problem);
    PrimitiveDesc prim;
    prim.base = renderer::BaseSurface(renderer::PlacedQuadric{quadric, m_state.ctm});
    SetPrimitiveAttributes(r, &prim);
    PatchColorFields(&prim, colors, 0, {0, 1, 2, 3}, {0, 1, 2, 3}, {}, false, false);
    m_scene.primitives.push_back(std::move(prim));
    return true;
}

// Points "P" [...] ("width" per point, or "constantwidth"; RI default width 1, in object space):
// each point a sphere of that diameter around it, with its own Cs and Os (constant or uniform:
// the whole request's; varying or vertex: the point's). prman draws points as discs facing the
// camera, which a ray tracer cannot tell apart from spheres at the sizes particles have: the
// silhouette is the same circle, and the shading a sphere's (a note says so once). A point of
// width 0 or less draws nothing. Every point is one quadric primitive of its own.
bool RibParser::DoPoints(const RibRequest& r) {
    std::vector<RibParam> params;
    if (!ParamList(r, 0, &params) || !InsideWorld(r)) return false;
    const std::string context = Quote(r.name);
    const RibParam* position = nullptr;
    for (const RibParam& p : params)
        if (p.value.name == "P") position = &p;
    if (!position) return Fail(r.at, context + " needs \"P\"");
    if (!position->value.strings.empty() || position->value.numbers.empty() || position->value.numbers.size() % 3 != 0)
        return Fail(position->at,
                    context + " parameter 'P' expects 3 numbers a point, got " +
                        (position->value.strings.empty() ? std::to_string(position->value.numbers.size()) + " numbers"
                                                         : std::string("strings")));
    const std::vector<double>& P = position->value.numbers;
    const size_t n = P.size() / 3;
    std::vector<double> widths(1, 1.0);  // one for every point, or one each
    std::optional<ColorValues> colors[2];
    const PrimvarCounts counts{1, n, n, n};
    for (const RibParam& p : params) {
        const std::string& name = p.value.name;
        if (name == "P") continue;
        if (name == "width" || name == "constantwidth") {
            const size_t got = p.value.numbers.size();
            if (!p.value.strings.empty() || !(got == 1 || (name == "width" && got == n)))
                return Fail(p.at, context + " parameter " + Quote(name) + " expects " +
                                      (name == "width" ? std::to_string(n) + " numbers (one a point) or 1"
                                                       : std::string("1 number")) +
                                      ", got " +
                                      (p.value.strings.empty() ? std::to_string(got) : std::string("strings")));
            widths = p.value.numbers;
        } else if (name == "Cs" || name == "Os") {
            ColorValues c;
            if (!ColorPrimvar(p, context, counts, true, &c)) return false;
            colors[name == "Os"] = std::move(c);
        } else {
            Warn(p.at, context + " parameter " + Quote(name) + " is not supported yet; ignored");
        }
    }
    Note(r.at, "'Points' are drawn as spheres of their width (prman draws discs facing the camera)");
    size_t skipped = 0;
    for (size_t i = 0; i < n; ++i) {
        const double width = widths[widths.size() == 1 ? 0 : i];
        if (!(width > 0)) {
            ++skipped;
            continue;
        }
        const double radius = 0.5 * width;
        const double v[4] = {radius, -radius, radius, 360};
        const Quadric sphere = MakeQuadric(Quadric::Kind::Sphere, v);
        if (std::string problem = sphere.Problem(); !problem.empty())
            return Fail(r.at, context + " point " + std::to_string(i) + ": " + problem);
        PrimitiveDesc prim;
        const glm::dvec3 at(P[3 * i], P[3 * i + 1], P[3 * i + 2]);
        prim.base = renderer::BaseSurface(renderer::PlacedQuadric{sphere, glm::translate(m_state.ctm, at)});
        SetPrimitiveAttributes(r, &prim);
        for (int k = 0; k < 2; ++k) {
            if (!colors[k]) continue;
            const std::vector<glm::dvec3>& values = colors[k]->values;
            (k == 0 ? prim.color : prim.opacity) = values[values.size() == 1 ? 0 : i];
        }
        m_scene.primitives.push_back(std::move(prim));
    }
    if (skipped > 0)
        Warn(r.at, context + ": " + std::to_string(skipped) + " point" + (skipped == 1 ? "" : "s") +
                       " of width 0 or less drawn as nothing");
    return true;
}

// CoordinateSystem names the current object space for the rest of the frame. Before WorldBegin
// that space is known only relative to the camera; WorldBegin maps it to world space, as it does
// lights. ScopedCoordinateSystem names it until the end of the attribute block (an attribute of
// the primitives after it, which see it over a CoordinateSystem of the same name); before
// WorldBegin, where no primitive can see it in a block, it is a CoordinateSystem.
bool RibParser::DoCoordinateSystem(const RibRequest& r) {
    std::string name;
    if (!LeadingString(r, "a coordinate system name", &name)) return false;
    if (r.args.size() > 1) return Fail(r.at, Quote(r.name) + " expects one string");
    if (m_worldEnded) return Fail(r.at, Quote(r.name) + " after 'WorldEnd'");
    static const char* const kStandard[] = {"camera", "current", "object", "raster",
                                            "screen", "shader",  "world",  "NDC"};
    for (const char* standard : kStandard)
        if (name == standard) return Fail(r.at, Quote(r.name) + " cannot redefine the standard space " + Quote(name));
    WarnIfMoving(r, "coordinate systems");
    if (m_worldSeen && r.name == "ScopedCoordinateSystem") {
        auto spaces = m_state.scopedSpaces ? std::make_shared<std::map<std::string, glm::dmat4>>(*m_state.scopedSpaces)
                                           : std::make_shared<std::map<std::string, glm::dmat4>>();
        (*spaces)[name] = m_state.ctm;
        m_state.scopedSpaces = std::move(spaces);
    } else if (m_worldSeen) {
        m_scene.coordinateSystems[name] = m_state.ctm;
    } else {
        if (!NoPendingPerspective(r)) return false;
        m_cameraCoordinateSystems[name] = m_state.ctm;
    }
    return true;
}

// CoordSysTransform replaces the current transform with a named space's: one that
// ScopedCoordinateSystem defined in the blocks open, or CoordinateSystem, or "world", "camera"
// (and "object", "current", "shader", which are the current space, so nothing changes). Screen
// spaces are projective and refused.
bool RibParser::DoCoordSysTransform(const RibRequest& r) {
    std::string name;
    if (!LeadingString(r, "a coordinate system name", &name)) return false;
    if (r.args.size() > 1) return Fail(r.at, "'CoordSysTransform' expects one string");
    if (name == "object" || name == "current" || name == "shader") return true;
    // The named space as the CTM holds it: object -> world inside the world block, object ->
    // camera before it (and after WorldEnd, as ObjectToCamera says).
    const bool inWorld = m_worldSeen && !m_worldEnded;
    const glm::dmat4& worldToCamera = m_scene.camera.worldToCamera;
    const auto named = m_scene.coordinateSystems.find(name);
    const auto beforeWorld = m_cameraCoordinateSystems.find(name);
    glm::dmat4 ctm;
    if (name == "camera") {
        ctm = inWorld ? glm::inverse(worldToCamera) : glm::dmat4(1.0);
    } else if (name == "world") {
        if (!m_worldSeen)
            return Fail(r.at, "'CoordSysTransform \"world\"' before 'WorldBegin': world space is not known yet");
        ctm = inWorld ? glm::dmat4(1.0) : worldToCamera;
    } else if (inWorld && m_state.scopedSpaces && m_state.scopedSpaces->count(name)) {
        ctm = m_state.scopedSpaces->at(name);
    } else if (named != m_scene.coordinateSystems.end()) {
        ctm = inWorld ? named->second : worldToCamera * named->second;
    } else if (beforeWorld != m_cameraCoordinateSystems.end()) {
        ctm = beforeWorld->second;  // only before WorldBegin, which moves them to world space
    } else {
        return Fail(r.args[0].at, "'CoordSysTransform': no coordinate system " + Quote(name) +
                                      " has been defined (by 'CoordinateSystem')");
    }
    m_state.perspectiveFov = 0;  // replaced with the rest of the CTM
    return SetCtm(r, ctm);
}

}  // namespace affray::rib
