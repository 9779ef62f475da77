// scene/refine.h: preparing a scene's meshes for rendering. The RIB reader keeps a polygon or
// subdivision mesh as it read it (an UnrefinedMesh on the mesh's PrimitiveDesc, which has no
// elements yet), so that reading stays cheap and the work happens where a render prepares its
// scene; RefineScene splits each polygon mesh into pieces (SplitMesh, scene/geometry/mesh.h) and
// refines each subdivision mesh into patches (BuildSubdivisionPatches,
// scene/geometry/subdivision.h), independent meshes at once. What only the refined mesh shows
// (a degenerate face, a broken topology, a patch that overflows) is reported here, at the mesh's
// request in the RIB file, as the reader would have reported it. A new kind of mesh that the
// reader hands over unrefined gets an alternative of UnrefinedMesh::mesh and a case in
// RefineScene's refinement; the renderer only ever sees refined meshes (Renderer::Prepare calls
// RefineScene first and refuses a primitive left unrefined).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <variant>

#include "diag/diagnostic.h"
#include "scene/geometry/mesh.h"
#include "scene/geometry/primvar.h"
#include "scene/geometry/subdivision.h"

namespace affray::renderer {

struct SceneDesc;

/// A polygon or subdivision mesh as the RIB reader read it (world space, counts and indices
/// checked), before it is split or refined; PrimitiveDesc::unrefined holds it until RefineScene.
struct UnrefinedMesh {
    std::variant<PolygonMesh, SubdivisionMesh> mesh;
    /// The mesh's "Cs" (colors[0]) and "Os" (colors[1]) if they vary over it (a constant one is
    /// already the primitive's colour): a polygon mesh's go to its PieceMesh as given; a
    /// subdivision mesh's uniform ones too (SubdivPatches::colors), the others are refined with
    /// the mesh (SubdivPatches::colorFields).
    std::optional<ColorValues> colors[2];
    /// The request, for messages: its name as the reader quotes it ("'PointsPolygons'"), where it
    /// is (file, line, column and source line), and the note that the reader gives with an error
    /// there, if any (the outermost ObjectInstance that made the mesh).
    std::string request;
    diag::Location at;
    std::optional<diag::Diagnostic> note;
};

/// Runs body(i) for every i in [0, n), possibly several at once on other threads, and returns
/// when every call has returned (the renderer passes its thread pool's ForEach).
using ParallelFor = std::function<void(size_t n, const std::function<void(size_t i)>& body)>;

/// Makes every mesh of `scene` that the reader left unrefined ready to render: a polygon mesh
/// split into its pieces, a subdivision mesh refined into its patches, each the elements of its
/// primitive, with the colours the UnrefinedMesh holds; a mesh that makes no elements (every face
/// a hole) is dropped. Meshes are refined through `parallelFor` if given (else one after the
/// other), each mesh's memory as read released once it is refined when the scene holds its only
/// reference (a caller's copy of the scene keeps its mesh). The result does not depend on
/// `parallelFor`. On a mesh that cannot be refined, returns false with one error in *report (may
/// be null) at the mesh's request, the first such mesh in the scene's order; the scene is then
/// partly refined.
bool RefineScene(SceneDesc* scene, diag::Report* report, const ParallelFor& parallelFor = {});

}  // namespace affray::renderer
