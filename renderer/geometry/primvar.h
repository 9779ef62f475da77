// renderer/geometry/primvar.h: what every mesh-like base surface shares about primitive variables.
#pragma once

namespace affray::renderer {

/// How a primitive variable's values map onto a primitive (RI Spec 3.2 section 4.1, table 4.1):
/// one value; one per face (patch, segment); one per point for Varying (interpolated bilinearly)
/// and Vertex (interpolated as P is); one per face corner. Polygon meshes, subdivision meshes
/// and NuPatches all read their "st" through it (a NuPatch has no FaceVarying: its reader says so).
enum class StorageClass { Constant, Uniform, Varying, Vertex, FaceVarying };

}  // namespace affray::renderer
