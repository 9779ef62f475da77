// rib/subdivision.cpp: RI Spec 3.2 section 5.5, SubdivisionMesh "catmull-clark" nvertices vertices
// [tags nargs intargs floatargs] parameterlist, and prman's HierarchicalSubdivisionMesh (what
// RenderMan 16 and later exporters write), the same with a fifth array, stringargs, and three
// nargs a tag; its hierarchical edits (tags that take strings) are warned about and ignored.
// The mesh becomes a renderer::SubdivisionMesh in world space, kept as read on one primitive
// (AddMesh, rib/polygons.cpp): renderer::RefineScene refines it into patches, the primitive's
// elements, when the scene is prepared (scene/refine.h, scene/geometry/subdivision.h), and
// reports at the request a topology it cannot refine. Tags: "hole" (face indices), "crease" (a
// chain of vertices, one sharpness), "corner" (vertices, one sharpness or one each),
// "interpolateboundary" (no argument, or one integer: 0 none, 1 edges and corners, 2 edges only);
// any other tag is warned about once and ignored. Parameters: "P" or "Pw" (w must be 1), "st" or
// "s" and "t" together (any storage class), "Cs" and "Os" (any storage class: vertex values
// follow the limit surface's rules, as P does; varying and facevarying ones are bilinear over
// each face); "N" means nothing on a subdivision surface (its normal is the limit surface's)
// and is ignored with a warning, as in PRMan; other variables are checked against their
// counts, then ignored with a warning.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "rib/parser.h"

namespace affray::rib {

using renderer::StorageClass;
using renderer::SubdivisionMesh;
using renderer::SubdivST;

bool RibParser::DoSubdivisionMesh(const RibRequest& r) {
    const std::string context = Quote(r.name);
    std::string scheme;
    if (!LeadingString(r, "a subdivision scheme name", &scheme)) return false;
    // Another scheme's surface is skipped, as an unsupported primitive is (rib/unsupported.cpp).
    if (scheme != "catmull-clark") {
        if (!InsideWorld(r)) return false;
        Warn(r.args[0].at,
             context + " scheme " + Quote(scheme) + " is not supported (only \"catmull-clark\"): the mesh is skipped");
        return true;
    }
    std::vector<int> nvertices, vertices;
    if (!IntArray(r, 1, "nvertices", 3, &nvertices) || !IntArray(r, 2, "vertices", 0, &vertices)) return false;
    // The tags come as four arrays (five for a HierarchicalSubdivisionMesh: its tags may take
    // strings too), or not at all (the parameter list's tokens are bare strings).
    const bool hierarchical = r.name == "HierarchicalSubdivisionMesh";
    const size_t perTag = hierarchical ? 3 : 2;  // entries of nargs per tag: integers, floats (, strings)
    const std::string argArrays = hierarchical ? "intargs, floatargs and stringargs" : "intargs and floatargs";
    size_t first = 3;
    std::vector<std::string> tags;
    std::vector<int> nargs, intargs;
    std::vector<double> floatargs;
    if (r.args.size() > 3 && r.args[3].isArray) {
        if (r.args.size() < 4 + perTag + 1 || !r.args[3].StringsP())
            return Fail(r.args[3].at, context + " expects the arrays tags, nargs, " + argArrays + " after vertices");
        tags = r.args[3].strings;
        for (size_t i = 4; i < 7; ++i)
            if (!r.args[i].isArray || !r.args[i].NumericP())
                return Fail(r.args[i].at, context + " expects an array of numbers as argument " +
                                              std::to_string(i + 1) + ", found " + r.args[i].Describe());
        if (hierarchical && !r.args[7].isArray)
            return Fail(r.args[7].at, context + " expects an array of strings (stringargs) as argument 8, found " +
                                          r.args[7].Describe());
        nargs.clear();
        for (double x : r.args[4].numbers) {
            if (x != std::floor(x) || x < 0 || x > 1e9)
                return Fail(r.args[4].at, context + " nargs must be integers of at least 0");
            nargs.push_back(static_cast<int>(x));
        }
        for (double x : r.args[5].numbers) {
            if (x != std::floor(x) || std::fabs(x) > 1e9)
                return Fail(r.args[5].at, context + " intargs must be integers, got " + FormatNumber(x));
            intargs.push_back(static_cast<int>(x));
        }
        floatargs = r.args[6].numbers;
        first = hierarchical ? 8 : 7;
    }
    std::vector<RibParam> params;
    m_uniformVaries = true;
    const bool listed = ParamList(r, first, &params);
    m_uniformVaries = false;
    if (!listed || !InsideWorld(r)) return false;

    // Counts and indices.
    const size_t nFaces = nvertices.size();
    const size_t nCorners = static_cast<size_t>(std::accumulate(nvertices.begin(), nvertices.end(), 0LL));
    if (vertices.size() != nCorners)
        return Fail(r.args[2].at, context + " nvertices add up to " + std::to_string(nCorners) +
                                      " vertices, but the vertices array has " + std::to_string(vertices.size()));
    MeshPoints points;
    if (!FindMeshPoints(r, params, context, &points)) return false;
    const RibParam* const position = points.param;
    const size_t width = points.width, nPoints = points.count;
    for (int v : vertices)
        if (static_cast<size_t>(v) >= nPoints)
            return Fail(r.args[2].at, context + " vertex index " + std::to_string(v) + " is out of range (" +
                                          Quote(position->value.name) + " has " + std::to_string(nPoints) + " points)");

    SubdivisionMesh mesh;
    mesh.faceSizes = nvertices;
    mesh.faceVerts = vertices;

    // Tags: each takes nargs[2i] integers and nargs[2i + 1] floats, in order (nargs[3i] and
    // nargs[3i + 1], and nargs[3i + 2] strings, in a HierarchicalSubdivisionMesh).
    if (nargs.size() != perTag * tags.size())
        return Fail(r.args[4].at, context + " has " + std::to_string(tags.size()) + " tags, so nargs needs " +
                                      std::to_string(perTag * tags.size()) + " entries, got " +
                                      std::to_string(nargs.size()));
    const size_t nStrings = hierarchical ? r.args[7].strings.size() : 0;
    size_t stringAt = 0;
    size_t intAt = 0, floatAt = 0;
    std::set<std::pair<int, int>> edges;
    for (size_t f = 0, c = 0; f < nFaces; c += static_cast<size_t>(nvertices[f]), ++f)
        for (int k = 0; k < nvertices[f]; ++k) {
            const int a = vertices[c + static_cast<size_t>(k)];
            const int b = vertices[c + static_cast<size_t>((k + 1) % nvertices[f])];
            edges.insert(std::minmax(a, b));
        }
    for (size_t i = 0; i < tags.size(); ++i) {
        const size_t ni = static_cast<size_t>(nargs[perTag * i]), nf = static_cast<size_t>(nargs[perTag * i + 1]);
        const size_t ns = hierarchical ? static_cast<size_t>(nargs[perTag * i + 2]) : 0;
        if (intAt + ni > intargs.size() || floatAt + nf > floatargs.size() || stringAt + ns > nStrings)
            return Fail(r.args[4].at, context + " nargs ask for more arguments than " + argArrays + " hold (tag " +
                                          Quote(tags[i]) + ")");
        stringAt += ns;
        const std::vector<int> ints(intargs.begin() + static_cast<long>(intAt),
                                    intargs.begin() + static_cast<long>(intAt + ni));
        const std::vector<double> floats(floatargs.begin() + static_cast<long>(floatAt),
                                         floatargs.begin() + static_cast<long>(floatAt + nf));
        intAt += ni;
        floatAt += nf;
        const std::string tag = context + " tag " + Quote(tags[i]);
        auto checkVertices = [&]() {
            for (int v : ints)
                if (v < 0 || static_cast<size_t>(v) >= nPoints)
                    return Fail(r.args[5].at, tag + " vertex index " + std::to_string(v) + " is out of range");
            return true;
        };
        if (tags[i] == "hole") {
            for (int f : ints) {
                if (f < 0 || static_cast<size_t>(f) >= nFaces)
                    return Fail(r.args[5].at, tag + " face index " + std::to_string(f) + " is out of range (" +
                                                  std::to_string(nFaces) + " faces)");
                mesh.holes.push_back(f);
            }
        } else if (tags[i] == "crease") {
            if (ints.size() < 2 || floats.size() != 1)
                return Fail(r.args[4].at, tag + " expects at least 2 vertex indices and 1 sharpness, got " +
                                              std::to_string(ints.size()) + " and " + std::to_string(floats.size()));
            if (!checkVertices()) return false;
            for (size_t k = 0; k + 1 < ints.size(); ++k)
                if (!edges.count(std::minmax(ints[k], ints[k + 1])))
                    return Fail(r.args[5].at, tag + " joins vertices " + std::to_string(ints[k]) + " and " +
                                                  std::to_string(ints[k + 1]) + ", which share no edge");
            mesh.creases.push_back({ints, floats[0]});
        } else if (tags[i] == "corner") {
            if (floats.size() != 1 && floats.size() != ints.size())
                return Fail(r.args[4].at,
                            tag + " expects 1 sharpness or one per vertex, got " + std::to_string(floats.size()));
            if (!checkVertices()) return false;
            for (size_t k = 0; k < ints.size(); ++k)
                mesh.corners.emplace_back(ints[k], floats.size() == 1 ? floats[0] : floats[k]);
        } else if (tags[i] == "interpolateboundary") {
            const int mode = ints.empty() ? 1 : ints[0];
            if (ints.size() > 1 || mode < 0 || mode > 2)
                return Fail(r.args[5].at, tag + " expects no argument or one of 0, 1, 2");
            mesh.boundary = mode == 0   ? renderer::SubdivBoundary::None
                            : mode == 1 ? renderer::SubdivBoundary::EdgesAndCorners
                                        : renderer::SubdivBoundary::EdgesOnly;
        } else {
            Warn(r.args[3].at, tag + " is not supported; ignored");
        }
    }

    // Primitive variables against their storage classes.
    const RibParam *sParam = nullptr, *tParam = nullptr;
    std::optional<ColorValues> colors[2];  // Cs, Os
    const PrimvarCounts counts{nFaces, nPoints, nCorners, nPoints};
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
        if (name == "P" || name == "Pw") continue;
        if (name == "N") {
            Warn(p.at, context +
                           " parameter \"N\" has no meaning on a subdivision surface (its normal is the limit "
                           "surface's); ignored");
        } else if (name == "st" && each == 2) {
            SubdivST st{storage, {}};
            for (size_t k = 0; k < values; ++k)
                st.values.emplace_back(p.value.numbers[2 * k], p.value.numbers[2 * k + 1]);
            mesh.st = st;
        } else if ((name == "s" || name == "t") && each == 1) {
            (name == "s" ? sParam : tParam) = &p;
        } else {
            Warn(p.at, context + " parameter " + Quote(name) + " is not supported yet; ignored");
        }
    }
    if (!mesh.st && (sParam || tParam)) {
        // "s" and "t" together make st; one alone cannot be mixed with the patch's own parameter.
        if (!sParam || !tParam || sParam->value.declaration != tParam->value.declaration)
            Warn((sParam ? sParam : tParam)->at,
                 context + " parameters \"s\" and \"t\" are used only together, with the same storage class; ignored");
        else {
            RibDeclaration d;
            std::string problem;
            const std::string declared =
                sParam->value.declaration.empty() ? "varying float" : sParam->value.declaration;
            RibDeclaration::Parse(declared, &d, &problem);
            SubdivST st{d.Storage(), {}};
            for (size_t k = 0; k < sParam->value.numbers.size(); ++k)
                st.values.emplace_back(sParam->value.numbers[k], tParam->value.numbers[k]);
            mesh.st = st;
        }
    }
    for (size_t i = 0; i < nPoints; ++i) {
        const double* v = position->value.numbers.data() + width * i;
        if (width == 4 && v[3] != 1)
            return Fail(position->at, context + " parameter 'Pw' has w = " + FormatNumber(v[3]) + " at point " +
                                          std::to_string(i) + ": rational subdivision meshes are not supported");
        mesh.points.push_back(TransformPoint(m_state.ctm, glm::dvec3(v[0], v[1], v[2])));
        if (!FiniteP(mesh.points.back()))
            return Fail(position->at, context + " point " + std::to_string(i) + " overflows in world space");
    }

    // The mesh as read, with its Cs and Os: the preparation of the scene refines it into
    // patches (scene/refine.h).
    AddMesh(r, std::move(mesh), colors);
    return true;
}

}  // namespace affray::rib
