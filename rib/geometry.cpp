// rib/geometry.cpp: RIB requests that place geometry: Patch, the quadrics (Sphere,
// Cylinder, Cone, Disk, Torus, Hyperboloid, Paraboloid) and CoordinateSystem. Rules shared with
// rib.cpp are in rib_parser.h. Every primitive takes the graphics state current at its request;
// its orientation is resolved here into PrimitiveDesc::flipNormal, since the camera transform it
// depends on is known once geometry is allowed (inside the world block).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "rib/parser.h"

namespace affray::rib {

// flipNormal = (det objectToWorld < 0) XOR insideOut, as documented in scene.h: the first term
// undoes the turn a mirroring placement gives dPdu x dPdv, the second applies the RI rule.
bool RibParser::FlipNormalP() const {
    const bool mirrored = glm::determinant(glm::dmat3(m_state.ctm)) < 0;
    return mirrored != m_state.insideOut;
}

void RibParser::SetPrimitiveAttributes(const RibRequest& r, PrimitiveDesc* p) const {
    p->color = m_state.color;
    p->surface = m_state.surface;
    p->displacement = m_state.displacement;
    p->line = r.at.line;
    p->column = r.at.column;
    p->objectToWorld = m_state.ctm;
    p->twoSided = m_state.twoSided;
    p->flipNormal = FlipNormalP();
}

bool RibParser::DoPatch(const RibRequest& r) {
    std::string type;
    if (!LeadingString(r, "a patch type", &type)) return false;
    if (type == "bicubic") return Fail(r.at, "'Patch \"bicubic\"' is not supported yet");
    if (type != "bilinear")
        return Fail(r.args[0].at, "unknown patch type " + Quote(type) + " (expected \"bilinear\" or \"bicubic\")");
    std::vector<RibParam> params;
    if (!ParamList(r, 1, &params) || !InsideWorld(r)) return false;

    const std::string context = "'Patch \"bilinear\"'";
    std::array<glm::dvec3, 4> corners{};
    bool havePosition = false;
    for (const RibParam& p : params) {
        const std::string& n = p.value.name;
        if (n == "P") {
            double v[12];
            if (!ParamNumbers(p, context, 12, v)) return false;
            for (size_t i = 0; i < 4; ++i) corners[i] = glm::dvec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        } else if (n == "Pw") {  // homogeneous points
            double v[16];
            if (!ParamNumbers(p, context, 16, v)) return false;
            for (size_t i = 0; i < 4; ++i) {
                if (v[4 * i + 3] == 0) return Fail(p.at, context + " parameter 'Pw' has a zero w");
                corners[i] = glm::dvec3(v[4 * i], v[4 * i + 1], v[4 * i + 2]) / v[4 * i + 3];
            }
        } else if (n == "Pz") {  // heights over the unit square (x = u, y = v)
            double z[4];
            if (!ParamNumbers(p, context, 4, z)) return false;
            for (int i = 0; i < 4; ++i) corners[i] = glm::dvec3(i & 1, i >> 1, z[i]);
        } else {
            Warn(p.at, context + " parameter " + Quote(n) + " is not supported yet; ignored");
            continue;
        }
        havePosition = true;
    }
    if (!havePosition) return Fail(r.at, context + " needs a \"P\" parameter");

    PrimitiveDesc patch;
    for (int i = 0; i < 4; ++i) {
        patch.corners[i] = TransformPoint(m_state.ctm, corners[i]);
        if (!FiniteP(patch.corners[i]))
            return Fail(r.at, context + " corner " + std::to_string(i) + " overflows in world space");
    }
    SetPrimitiveAttributes(r, &patch);
    m_scene.primitives.push_back(std::move(patch));
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

}  // namespace

bool RibParser::DoQuadric(const RibRequest& r, Quadric::Kind kind) {
    const char* names = QuadricArgNames(kind);
    const size_t count = 1 + std::count(names, names + std::strlen(names), ' ');
    double v[7];
    size_t next = 0;
    std::vector<RibParam> params;
    if (!LeadingNumbers(r, count, names, v, &next) || !ParamList(r, next, &params) || !InsideWorld(r)) return false;
    // Primitive variables (Cs, st, N, ...) would vary over the surface; none is used yet.
    for (const RibParam& p : params)
        Warn(p.at, Quote(r.name) + " parameter " + Quote(p.value.name) + " is not supported yet; ignored");

    PrimitiveDesc prim;
    prim.shape = PrimitiveDesc::Shape::Quadric;
    prim.quadric = MakeQuadric(kind, v);
    if (std::string problem = prim.quadric.Problem(); !problem.empty())
        return Fail(r.at, Quote(r.name) + " " + problem);
    SetPrimitiveAttributes(r, &prim);
    m_scene.primitives.push_back(std::move(prim));
    return true;
}

// CoordinateSystem names the current object space. Before WorldBegin that space is known only
// relative to the camera; WorldBegin maps it to world space, as it does lights.
bool RibParser::DoCoordinateSystem(const RibRequest& r) {
    std::string name;
    if (!LeadingString(r, "a coordinate system name", &name)) return false;
    if (r.args.size() > 1) return Fail(r.at, "'CoordinateSystem' expects one string");
    if (m_worldEnded) return Fail(r.at, "'CoordinateSystem' after 'WorldEnd'");
    static const char* const kStandard[] = {"camera", "current", "object", "raster",
                                            "screen", "shader",  "world",  "NDC"};
    for (const char* standard : kStandard)
        if (name == standard) return Fail(r.at, "'CoordinateSystem' cannot redefine the standard space " + Quote(name));
    if (m_worldSeen)
        m_scene.coordinateSystems[name] = m_state.ctm;
    else
        m_cameraCoordinateSystems[name] = m_state.ctm;
    return true;
}

// CoordSysTransform replaces the current transform with a named space's: one that
// CoordinateSystem defined, or "world", "camera" (and "object", "current", "shader", which are
// the current space, so nothing changes). Screen spaces are projective and refused.
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
    } else if (named != m_scene.coordinateSystems.end()) {
        ctm = inWorld ? named->second : worldToCamera * named->second;
    } else if (beforeWorld != m_cameraCoordinateSystems.end()) {
        ctm = beforeWorld->second;  // only before WorldBegin, which moves them to world space
    } else {
        return Fail(r.args[0].at, "'CoordSysTransform': no coordinate system " + Quote(name) +
                                      " has been defined (by 'CoordinateSystem')");
    }
    return SetCtm(r, ctm);
}

}  // namespace affray::rib
