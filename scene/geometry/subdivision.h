// scene/geometry/subdivision.h: Catmull-Clark subdivision meshes (RI Spec 3.2 section 5.5,
// RiSubdivisionMesh) as displaced base surfaces, one bicubic patch per face of a refined mesh.
// Owns the refinement (with RenderMan's tags), the patches and their templated evaluation for
// every number type; the RIB reader (rib/subdivision.cpp) makes a SubdivisionMesh, and the
// preparation of the scene (RefineScene, scene/refine.h) asks BuildSubdivisionPatches for its
// patches, the elements of one primitive.
//
// Refinement. The control mesh is refined uniformly: kSubdivisionLevels Catmull-Clark steps
// (fewer for a dense mesh, kSubdivisionPatchBudget; more, up to kMaxSubdivisionLevels, while a
// semi-sharp crease is left), or none when every face already is a regular quad. After one step every face is a quad with at most one
// extraordinary vertex (valence != 4); after two, such faces are a sixteenth of each face
// around an extraordinary vertex, so the approximation below covers little of the surface.
// Sharp rules (DeRose, Kass and Truong 1998): an edge of sharpness s >= 1 is split at its
// midpoint, one of 0 < s < 1 by the blend of the smooth and sharp points; a vertex with two
// sharp edges takes the crease rule (a + 6v + b) / 8 (blended by their mean sharpness if it is
// below 1), with three or more or a "corner" tag it stays put. Children of a sharp edge have
// sharpness s - 1. Boundary edges are always sharp (they have one face). Holes are refined
// like other faces and their children are not rendered.
//
// Patches. A face whose four corners are interior, of valence 4, with no sharp edge or corner
// tag, is exactly the uniform bicubic B-spline patch of its 16 control points (RenderMan's
// limit surface there), converted to the power basis of BicubicPatch. Every other face is
// approximated by a bicubic Bezier patch after Loop and Schaefer ("Approximating Catmull-Clark
// subdivision surfaces with bicubic patches", ACM TOG 2008): its corners are limit positions, the
// two inner points of each edge come from the limit tangents of the edge's end vertices (so an
// edge's curve depends only on its two vertices' rings, and both faces build it from the same
// doubles), the interior points are their face-corner averages. With valence 4 the formulas give
// the B-spline patch's Bezier points, so the construction is exact wherever the mesh is regular.
// Feature vertices: a crease vertex (two sharp edges, a, b along them) has limit (a + 4v + b)/6
// and edge points (2v + a)/3, (2v + b)/3 along the crease (the crease's limit is the cubic
// B-spline of its vertices); a corner vertex is its own limit. Their other edge points and
// interior points use the regular (valence 4) formulas. Deviation from the true limit surface:
// see kAccDeviation (measured in tests/scene/geometry/subdivision_test.cpp).
//
// No cracks. A displacement moves P along N, so neighbours must agree on P and on N's
// direction along every shared edge. P: they share the boundary curve (its four Bezier points
// are the same doubles). N: a regular patch uses its geometric normal dPdu x dPdv, which is
// continuous (the surface is C2 there). An approximated patch instead gets a normal direction
// field (SurfaceFrame::normalDirection):
//     n(u,v) = bilinear(n00, n10, n01, n11) + sum over edges k of bubble_k(u,v) Q_k(t_k)
// where n_ij are per-vertex normals (one double triple per vertex, shared), bubble_k is
// t(1-t) times the blend toward edge k (e.g. (1-v) u (1-u) for edge v = 0) and Q_k a cubic per
// edge, computed once per edge and shared by its two faces (one reads it reversed). On edge k
// every other bubble vanishes, so n there is the edge curve
//     E(t) = n_a (1-t) + n_b t + t(1-t) Q(t),
// the same polynomial from both faces in real arithmetic. E is fitted to T(t) x C(t), T the
// boundary curve's tangent and C = (D_A - D_B)/2 the mean of the two faces' cross-boundary
// derivatives (one-sided on a boundary), and n_v is the mean of T x C at v over v's edges. Where
// both ends of an edge are regular vertices the patches on either side are C1 (D_B = -D_A), so
// E is then exactly the geometric normal that a regular neighbour uses, and n_v the limit
// normal; at an extraordinary vertex every T x C is the same multiple of the limit normal, so
// the corner normals are the limit normals. The double coefficients of neighbours differ only
// by rounding of their set-up (as those of a PatchMesh's patches do), far below any tolerance.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/geometry/bicubic.h"
#include "scene/geometry/primvar.h"
#include "scene/geometry/quadric.h"
#include "vm/numbers/number.h"
#include "vm/numbers/vec3.h"

namespace affray::renderer {

/// Catmull-Clark steps before patches are built (fewer only when every face is already regular).
inline constexpr int kSubdivisionLevels = 2;
/// The patches the default steps may make: a control mesh of more than a 16th as many faces takes
/// fewer steps (one, or none if its faces are all quads). Its faces are then small: the
/// approximated patches' deviation from the limit surface is a fraction of a face's size
/// (kAccDeviation is measured on meshes of a few faces), and a 100,000-face mesh makes 100,000
/// patches, not 1.6 million (2.5 GB).
inline constexpr size_t kSubdivisionPatchBudget = size_t{1} << 16;
/// The most steps taken to resolve semi-sharp creases (sharpness left after them counts as sharp).
inline constexpr int kMaxSubdivisionLevels = 4;
/// A bound on the distance, relative to the mesh's bounding box diagonal, between the patches and
/// the limit surface (limit points of the mesh refined four times) for the test meshes at
/// kSubdivisionLevels: measured 9.2e-5 for the cube (valence 3) and 1.3e-4 for a prism capped
/// by a pyramid (a pentagon, triangles, valence 3 to 5): see subdivision_test.cpp.
inline constexpr double kAccDeviation = 3e-4;

/// How the mesh's "interpolateboundary" tag treats its boundary (RenderMan's values).
enum class SubdivBoundary {
    None,             ///< No tag: control faces with a boundary vertex shape the surface but are not rendered.
    EdgesAndCorners,  ///< 1 (the tag without arguments): boundary curves are B-splines, corners interpolated.
    EdgesOnly,        ///< 2: boundary curves are B-splines, valence-2 corners stay smooth.
};

/// A primitive variable "st" of a subdivision mesh: 2 numbers per value, by storage class.
struct SubdivST {
    StorageClass storage = StorageClass::Vertex;
    std::vector<glm::dvec2> values;
};

/// A primitive variable of a subdivision mesh that the caller reads back per patch ("Cs", "Os"):
/// 3 numbers per value, by storage class. Vertex values are refined and evaluated as P is (the
/// limit surface's rules); the others are bilinear over each face (RenderMan's varying).
struct SubdivVariable {
    StorageClass storage = StorageClass::Vertex;
    std::vector<glm::dvec3> values;
};

/// A subdivision mesh as RenderMan gives it, in world space: face f has faceSizes[f] corners,
/// corner c is points[faceVerts[c]]; tags already checked against the counts.
struct SubdivisionMesh {
    std::vector<glm::dvec3> points;
    std::vector<int> faceSizes, faceVerts;
    struct Crease {
        std::vector<int> chain;  ///< Vertices; each consecutive pair must be an edge.
        double sharpness = 0;
    };
    std::vector<Crease> creases;
    std::vector<std::pair<int, double>> corners;  ///< Vertex and sharpness (> 0: sharp).
    std::vector<int> holes;                       ///< Faces not rendered.
    SubdivBoundary boundary = SubdivBoundary::None;
    std::optional<SubdivST> st;
    std::vector<SubdivVariable> variables;
};

/// One rendered patch: face `face` of the refined mesh (from control face `controlFace`).
/// P is `geometry` over (u,v) in [0,1]^2; u runs from the face's corner 0 to corner 1, v from
/// corner 0 to corner 3, so dPdu x dPdv points as the face's winding does.
struct SubdivPatch {
    BicubicPatch geometry;
    /// Regular patches use the geometric normal; the others the field of the file head.
    bool regular = true;
    /// Normal field: corner normals at (0,0), (1,0), (0,1), (1,1) (RenderMan's patch order),
    /// and per edge (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0) the power coefficients of Q and
    /// whether Q's parameter runs against the face's u or v (the edge stored reversed).
    std::array<glm::dvec3, 4> cornerNormal{};
    std::array<std::array<glm::dvec3, 4>, 4> edgeQ{};
    std::array<bool, 4> edgeReversed{};
    /// s and t (in x and y) over the patch, if the mesh has "st" (else s, t are u, v).
    bool hasST = false;
    BicubicPatch st;
    int controlFace = 0;
};

/// The one-line description of a patch, for logs and tests.
std::string ToString(const SubdivPatch& p);

/// A subdivision mesh's patches as a scene keeps them: one object that every patch's primitive
/// shares (each an index into it), with the mesh's "Cs" (k = 0) and "Os" (k = 1).
struct SubdivPatches {
    std::vector<SubdivPatch> patches;
    /// A constant or uniform colour's values (one per control face), if the mesh has one.
    std::optional<ColorValues> colors[2];
    /// A colour that varies within a face: its field per patch, refined with the mesh (as
    /// SubdivPatch::st is); empty if none.
    std::vector<std::array<glm::dvec3, 16>> colorFields[2];

    /// Colour k over patch `index`'s (u,v) into *out; false if the mesh has no colour k.
    bool PatchColor(size_t index, int k, ColorField* out) const;
};

/// The refined mesh and its patches, for tests (BuildSubdivisionPatches's work).
struct SubdivisionResult {
    std::vector<SubdivPatch> patches;
    int levels = 0;
    int regularPatches = 0;
    /// Limit positions of the refined mesh's vertices (tests compare them with the patches).
    std::vector<glm::dvec3> refinedPoints;
    /// Per variable of the mesh, per patch (as `patches`): the variable over the patch's (u,v),
    /// as SubdivPatch::st is.
    std::vector<std::vector<BicubicPatch>> variables;
};

/// Refines `mesh` and builds one patch per rendered face (holes and, without
/// interpolateboundary, faces touching the boundary left out). Returns "" or what is wrong with
/// the mesh's topology ("edge 3-7 is shared by 3 faces"). `levels` < 0: the default rule above.
std::string BuildSubdivisionPatches(const SubdivisionMesh& mesh, SubdivisionResult* out, int levels = -1);

/// `mesh` after `levels` Catmull-Clark steps with its tags (for tests: deep refinement converges
/// to the limit surface). Faces and points in the same layout; tags carried over.
SubdivisionMesh RefineSubdivisionMesh(const SubdivisionMesh& mesh, int levels);

namespace subdiv_detail {
/// c[0] + c[1] x + c[2] x^2 + c[3] x^3 componentwise, zero coefficients skipped.
template <class T>
vm::Vec3<T> Cubic(const std::array<glm::dvec3, 4>& c, const T& x) {
    vm::Vec3<T> r;
    for (int i = 0; i < 3; ++i) {
        const double k[4] = {c[0][i], c[1][i], c[2][i], c[3][i]};
        r[i] = bicubic_detail::Horner(k, 3, x);
    }
    return r;
}
}  // namespace subdiv_detail

/// P, its tangents and (for an approximated patch) the normal direction field of the file head
/// at (u, v), in any number type.
template <class T>
SurfaceFrame<T> SubdivPatchFrame(const SubdivPatch& patch, const T& u, const T& v) {
    SurfaceFrame<T> f = BicubicFrame(patch.geometry, u, v);
    if (patch.regular) return f;
    using subdiv_detail::Cubic;
    const T one(1.0);
    const T u1 = one - u, v1 = one - v;
    const T bu = u * u1, bv = v * v1;
    const auto& n = patch.cornerNormal;
    // Each edge's Q at its own parameter: u or v, or 1 - u, 1 - v where it is stored reversed.
    const vm::Vec3<T> q0 = Cubic(patch.edgeQ[0], patch.edgeReversed[0] ? u1 : u);
    const vm::Vec3<T> q1 = Cubic(patch.edgeQ[1], patch.edgeReversed[1] ? v1 : v);
    const vm::Vec3<T> q2 = Cubic(patch.edgeQ[2], patch.edgeReversed[2] ? u1 : u);
    const vm::Vec3<T> q3 = Cubic(patch.edgeQ[3], patch.edgeReversed[3] ? v1 : v);
    const T w00 = u1 * v1, w10 = u * v1, w01 = u1 * v, w11 = u * v;
    const T b0 = bu * v1, b1 = bv * u, b2 = bu * v, b3 = bv * u1;
    for (int i = 0; i < 3; ++i)
        f.normalDirection[i] = w00 * n[0][i] + w10 * n[1][i] + w01 * n[2][i] + w11 * n[3][i] + b0 * q0[i] + b1 * q1[i] +
                               b2 * q2[i] + b3 * q3[i];
    f.hasNormalDirection = true;
    return f;
}

/// s and t of `patch` at (u, v): the mesh's "st" if it has one, else u and v.
template <class T>
void SubdivPatchST(const SubdivPatch& patch, const T& u, const T& v, T* s, T* t) {
    if (!patch.hasST) {
        *s = u;
        *t = v;
        return;
    }
    const SurfaceFrame<T> f = BicubicFrame(patch.st, u, v);
    *s = f.P.x;
    *t = f.P.y;
}

}  // namespace affray::renderer
