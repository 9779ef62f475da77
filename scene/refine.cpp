// scene/refine.cpp: RefineScene (scene/refine.h), the split and refinement of the meshes the RIB
// reader leaves as read, with the checks of their results.
#include "scene/refine.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace affray::renderer {

namespace {

/// `part` of `unrefined`, to refine: taken from it when `unrefined` is its only reference (the
/// memory as read goes with the refinement), else copied (another scene shares it).
template <class T>
T Take(const std::shared_ptr<UnrefinedMesh>& unrefined, T& part) {
    if (unrefined.use_count() == 1) return std::move(part);
    return part;
}

/// Splits the polygon mesh of `prim` into pieces, its elements; "" or what is wrong.
std::string SplitPolygons(PrimitiveDesc* prim) {
    const std::shared_ptr<UnrefinedMesh>& unrefined = prim->unrefined;
    auto split = std::make_shared<PieceMesh>();
    const std::string problem = SplitMesh(Take(unrefined, std::get<PolygonMesh>(unrefined->mesh)), split.get());
    if (!problem.empty()) return problem;
    if (split->pieces.size() > std::numeric_limits<uint32_t>::max()) return "has more than 2^32 - 1 pieces";
    for (int k = 0; k < 2; ++k) split->colors[k] = Take(unrefined, unrefined->colors[k]);
    prim->elements = static_cast<uint32_t>(split->pieces.size());
    BaseSurface base(MeshPieceRef{std::move(split), 0}, prim->base.flipNormal);
    base.textureCoordinates = prim->base.textureCoordinates;
    prim->base = std::move(base);
    return {};
}

/// Refines the subdivision mesh of `prim` into patches, its elements (none if every face is a
/// hole or, without interpolateboundary, on the boundary); "" or what is wrong.
std::string RefineSubdivision(PrimitiveDesc* prim) {
    const std::shared_ptr<UnrefinedMesh>& unrefined = prim->unrefined;
    SubdivisionMesh mesh = Take(unrefined, std::get<SubdivisionMesh>(unrefined->mesh));
    // Cs and Os that vary within a face are refined with the mesh (vertex values as P is, the
    // others bilinear in each face); a uniform one is each patch's colour.
    std::optional<ColorValues> colors[2] = {Take(unrefined, unrefined->colors[0]),
                                            Take(unrefined, unrefined->colors[1])};
    int variable[2] = {-1, -1};
    for (int k = 0; k < 2; ++k)
        if (colors[k] && colors[k]->storage != StorageClass::Uniform) {
            variable[k] = static_cast<int>(mesh.variables.size());
            mesh.variables.push_back({colors[k]->storage, std::move(colors[k]->values)});
        }
    SubdivisionResult result;
    if (std::string problem = BuildSubdivisionPatches(mesh, &result); !problem.empty()) return problem;
    for (const SubdivPatch& patch : result.patches)
        if (!patch.geometry.FiniteP()) return "has a patch that overflows in world space";
    if (result.patches.size() > std::numeric_limits<uint32_t>::max()) return "has more than 2^32 - 1 patches";
    auto patches = std::make_shared<SubdivPatches>();
    for (int k = 0; k < 2; ++k) {
        if (!colors[k]) continue;
        if (variable[k] < 0) {
            patches->colors[k] = std::move(colors[k]);
            continue;
        }
        for (const BicubicPatch& values : result.variables[size_t(variable[k])])
            patches->colorFields[k].push_back(values.c);
    }
    patches->patches = std::move(result.patches);
    prim->elements = static_cast<uint32_t>(patches->patches.size());
    BaseSurface base(SubdivPatchRef{std::move(patches), 0}, prim->base.flipNormal);
    base.textureCoordinates = prim->base.textureCoordinates;
    prim->base = std::move(base);
    return {};
}

}  // namespace

bool RefineScene(SceneDesc* scene, diag::Report* report, const ParallelFor& parallelFor) {
    std::vector<PrimitiveDesc*> meshes;
    for (PrimitiveDesc& p : scene->primitives)
        if (p.unrefined) meshes.push_back(&p);
    if (meshes.empty()) return true;
    // Each mesh refined on its own (its primitive its own), what is wrong kept per mesh; the
    // mesh as read is let go as soon as it is refined.
    std::vector<std::string> problems(meshes.size());
    auto refine = [&](size_t i) {
        PrimitiveDesc* prim = meshes[i];
        problems[i] =
            std::holds_alternative<PolygonMesh>(prim->unrefined->mesh) ? SplitPolygons(prim) : RefineSubdivision(prim);
        if (problems[i].empty()) prim->unrefined.reset();
    };
    if (parallelFor && meshes.size() > 1)
        parallelFor(meshes.size(), refine);
    else
        for (size_t i = 0; i < meshes.size(); ++i) refine(i);
    // The first problem in the scene's order, whichever thread met it first.
    for (size_t i = 0; i < meshes.size(); ++i) {
        if (problems[i].empty()) continue;
        const UnrefinedMesh& mesh = *meshes[i]->unrefined;
        if (report) {
            report->error(mesh.at, mesh.request + " " + problems[i]);
            if (mesh.note) report->note(mesh.note->where, mesh.note->message);
        }
        return false;
    }
    std::erase_if(scene->primitives, [](const PrimitiveDesc& p) { return p.elements == 0; });
    return true;
}

}  // namespace affray::renderer
