// rib/polygons.cpp: the polygon requests of RI Spec 3.2 section 5.1: Polygon, GeneralPolygon,
// PointsPolygons and PointsGeneralPolygons. Each becomes a renderer::PolygonMesh in world space,
// kept as read on one primitive (AddMesh, which SubdivisionMesh shares): renderer::RefineScene
// cuts it into pieces, the primitive's elements, when the scene is prepared (scene/refine.h), and
// reports at the request the faces it cannot cut. The parameter list is checked against the
// mesh's counts per storage class (RI 3.2 section 4.1): constant 1, uniform one per polygon,
// varying and vertex one per point, facevarying one per polygon corner (hole corners included).
// Only "P", "Pw", "N", "st", "s", "t", "Cs" and "Os" are used; other variables are checked, then
// ignored with a warning.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "rib/parser.h"

namespace affray::rib {

using renderer::MeshVariable;
using renderer::PolygonMesh;
using renderer::StorageClass;

bool RibParser::IntArray(const RibRequest& r, size_t index, const char* what, int least, std::vector<int>* out) {
    if (index >= r.args.size() || !r.args[index].strings.empty() || r.args[index].numbers.empty())
        return Fail(
            index < r.args.size() ? r.args[index].at : r.at,
            Quote(r.name) + " expects an array of integers " + what + " as argument " + std::to_string(index + 1));
    out->clear();
    for (double x : r.args[index].numbers) {
        if (x != std::floor(x) || x < least || x > 1e9)
            return Fail(r.args[index].at, Quote(r.name) + " " + what + " must be integers of at least " +
                                              std::to_string(least) + ", got " + FormatNumber(x));
        out->push_back(static_cast<int>(x));
    }
    return true;
}

bool RibParser::DoPolygon(const RibRequest& r) {
    // The corners are the points in order: their count comes from the parameter list.
    return MeshRequest(r, {1}, {}, {}, 0, false);
}

bool RibParser::DoGeneralPolygon(const RibRequest& r) {
    std::vector<int> nverts;
    if (!IntArray(r, 0, "nverts", 3, &nverts)) return false;
    return MeshRequest(r, {static_cast<int>(nverts.size())}, nverts, {}, 1, false);
}

bool RibParser::DoPointsPolygons(const RibRequest& r) {
    std::vector<int> nverts, vertices;
    if (!IntArray(r, 0, "nverts", 3, &nverts) || !IntArray(r, 1, "vertices", 0, &vertices)) return false;
    return MeshRequest(r, std::vector<int>(nverts.size(), 1), nverts, vertices, 2, true);
}

bool RibParser::DoPointsGeneralPolygons(const RibRequest& r) {
    std::vector<int> nloops, nverts, vertices;
    if (!IntArray(r, 0, "nloops", 1, &nloops) || !IntArray(r, 1, "nverts", 3, &nverts) ||
        !IntArray(r, 2, "vertices", 0, &vertices))
        return false;
    return MeshRequest(r, nloops, nverts, vertices, 3, true);
}

bool RibParser::MeshRequest(const RibRequest& r, std::vector<int> loops, std::vector<int> loopSizes,
                            std::vector<int> corners, size_t first, bool indexed) {
    std::vector<RibParam> params;
    m_uniformVaries = true;
    const bool listed = ParamList(r, first, &params);
    m_uniformVaries = false;
    if (!listed || !InsideWorld(r)) return false;
    const std::string context = Quote(r.name);
    const size_t nLoops = static_cast<size_t>(std::accumulate(loops.begin(), loops.end(), 0LL));
    if (nLoops != loopSizes.size() && !(r.name == "Polygon"))
        return Fail(r.args[1].at, context + " nloops add up to " + std::to_string(nLoops) + " loops, but nverts has " +
                                      std::to_string(loopSizes.size()) + " entries");

    // The points: "P" (or "Pw"), whose count a Polygon takes as its corner count.
    MeshPoints points;
    if (!FindMeshPoints(r, params, context, &points)) return false;
    const RibParam* const position = points.param;
    const size_t width = points.width, nPoints = points.count;
    if (r.name == "Polygon") {
        if (nPoints < 3)
            return Fail(position->at, context + " needs at least 3 points, got " + std::to_string(nPoints));
        loopSizes = {static_cast<int>(nPoints)};
    }
    const size_t nCorners = static_cast<size_t>(std::accumulate(loopSizes.begin(), loopSizes.end(), 0LL));
    if (!indexed) {
        corners.resize(nCorners);
        std::iota(corners.begin(), corners.end(), 0);
        if (nPoints != nCorners)
            return Fail(position->at, context + " has " + std::to_string(nCorners) + " vertices (by nverts) but " +
                                          std::to_string(nPoints) + " points in " + Quote(position->value.name));
    } else {
        const RibArg& vertexArg = r.args[first - 1];
        if (corners.size() != nCorners)
            return Fail(vertexArg.at, context + " nverts add up to " + std::to_string(nCorners) +
                                          " vertices, but the vertices array has " + std::to_string(corners.size()));
        for (int c : corners)
            if (static_cast<size_t>(c) >= nPoints)
                return Fail(vertexArg.at, context + " vertex index " + std::to_string(c) + " is out of range (" +
                                              Quote(position->value.name) + " has " + std::to_string(nPoints) +
                                              " points)");
    }

    // Every parameter against its storage class; the ones the mesh uses are kept.
    PolygonMesh mesh;
    mesh.loops = std::move(loops);
    mesh.loopSizes = std::move(loopSizes);
    mesh.corners = std::move(corners);
    const glm::dmat3 normalToWorld = glm::transpose(glm::inverse(glm::dmat3(m_state.ctm)));
    std::optional<ColorValues> colors[2];  // Cs, Os
    const PrimvarCounts counts{mesh.loops.size(), nPoints, nCorners, nPoints};
    for (const RibParam& p : params) {
        const std::string& name = p.value.name;
        if (name == "Cs" || name == "Os") {  // their own checks, for every primitive
            ColorValues c;
            if (!ColorPrimvar(p, context, counts, true, &c)) return false;
            colors[name == "Os"] = std::move(c);
            continue;
        }
        RibDeclaration d;
        bool declared;
        if (!MeshPrimvar(p, context, counts, &d, &declared)) return false;
        if (!declared) continue;
        const StorageClass storage = d.Storage();
        const size_t values = counts.Of(storage), each = d.UniformCount();
        MeshVariable var{storage, static_cast<int>(each), p.value.numbers};
        if (name == "P" || name == "Pw") continue;  // read below
        if (name == "N" && each == 3) {
            for (size_t i = 0; i < values; ++i) {
                const glm::dvec3 n =
                    normalToWorld * glm::dvec3(var.values[3 * i], var.values[3 * i + 1], var.values[3 * i + 2]);
                if (!FiniteP(n) || n == glm::dvec3(0.0))
                    return Fail(p.at, context + " normal " + std::to_string(i) + " is zero or not finite");
                for (int k = 0; k < 3; ++k) var.values[3 * i + static_cast<size_t>(k)] = n[k];
            }
            mesh.normals = std::move(var);
        } else if (name == "st" && each == 2) {
            mesh.st = std::move(var);
        } else if ((name == "s" || name == "t") && each == 1) {
            (name == "s" ? mesh.s : mesh.t) = std::move(var);
        } else {
            Warn(p.at, context + " parameter " + Quote(name) + " is not supported yet; ignored");
        }
    }
    mesh.points.reserve(nPoints);
    for (size_t i = 0; i < nPoints; ++i) {
        const double* v = position->value.numbers.data() + width * i;
        glm::dvec3 local(v[0], v[1], v[2]);
        if (width == 4) {
            if (v[3] == 0) return Fail(position->at, context + " parameter 'Pw' has a zero w");
            local /= v[3];
        }
        mesh.points.push_back(TransformPoint(m_state.ctm, local));
        if (!FiniteP(mesh.points.back()))
            return Fail(position->at, context + " point " + std::to_string(i) + " overflows in world space");
    }

    // The mesh as read: the preparation of the scene splits it into pieces (scene/refine.h).
    AddMesh(r, std::move(mesh), colors);
    return true;
}

void RibParser::AddMesh(const RibRequest& r, std::variant<renderer::PolygonMesh, renderer::SubdivisionMesh> mesh,
                        std::optional<ColorValues> (&colors)[2]) {
    // A constant Cs or Os is the primitive's colour, any other the mesh's.
    PrimitiveDesc prim;
    SetPrimitiveAttributes(r, &prim);
    SetConstantColors(colors, &prim);
    auto unrefined = std::make_shared<renderer::UnrefinedMesh>();
    unrefined->mesh = std::move(mesh);
    for (int k = 0; k < 2; ++k)
        if (colors[k] && colors[k]->storage != StorageClass::Constant) unrefined->colors[k] = std::move(colors[k]);
    unrefined->request = Quote(r.name);
    unrefined->at = Where(r.at);
    if (m_instanceNote)
        unrefined->note =
            diag::Diagnostic{diag::Severity::Note, Where(m_instanceNote->first), m_instanceNote->second, {}};
    prim.elements = 0;
    prim.unrefined = std::move(unrefined);
    m_scene.primitives.push_back(std::move(prim));
}

bool RibParser::FindMeshPoints(const RibRequest& r, const std::vector<RibParam>& params, const std::string& context,
                               MeshPoints* out) {
    const RibParam* position = nullptr;
    for (const RibParam& p : params)
        if (p.value.name == "P" || (p.value.name == "Pw" && !position)) position = &p;
    if (!position) return Fail(r.at, context + " needs a \"P\" parameter");
    const size_t width = position->value.name == "P" ? 3 : 4;
    const size_t count = position->value.numbers.size() / width;
    if (!position->value.strings.empty() || position->value.numbers.size() % width != 0 || count == 0)
        return Fail(position->at, context + " parameter " + Quote(position->value.name) + " expects a multiple of " +
                                      std::to_string(width) + " numbers, got " +
                                      std::to_string(position->value.numbers.size()));
    *out = {position, width, count};
    return true;
}

bool RibParser::MeshPrimvar(const RibParam& p, const std::string& context, const PrimvarCounts& counts,
                            RibDeclaration* d, bool* declared) {
    const std::string& name = p.value.name;
    const std::string declaration = p.value.declaration.empty() ? StandardDeclaration(name) : p.value.declaration;
    *declared = !declaration.empty();
    if (!*declared) {
        Warn(p.at, context + " parameter " + Quote(name) + " is not declared; ignored");
        return true;
    }
    std::string problem;
    if (!RibDeclaration::Parse(declaration, d, &problem)) return Fail(p.at, context + " parameter: " + problem);
    ResolveStorage(p, context, counts, true, d);
    const size_t values = counts.Of(d->Storage()), each = d->UniformCount();
    const size_t got = d->type == "string" ? p.value.strings.size() : p.value.numbers.size();
    if (got != values * each)
        return Fail(p.at, context + " parameter " + Quote(name) + " (" + declaration + ") expects " +
                              std::to_string(values) + " value" + (values == 1 ? "" : "s") + " of " +
                              std::to_string(each) + (each == 1 ? " number" : " numbers") + ", got " +
                              std::to_string(got) + (got == 1 ? " number" : " numbers"));
    return true;
}

}  // namespace affray::rib
