// scene/geometry/mesh.h: polygon meshes as base surfaces, one (u,v) piece per quad or triangle.
// Owns the split of RenderMan's polygons (Polygon, GeneralPolygon, PointsPolygons,
// PointsGeneralPolygons: RI Spec 3.2, section 5.1) into pieces, and the templated evaluation of a
// piece for every number type, as quadric.h owns the quadrics'. A piece is one primitive for the
// intersector; the RIB reader makes a PolygonMesh, and the preparation of the scene
// (RefineScene, scene/refine.h) asks SplitMesh for its pieces.
//
// Parameterisation. A piece is RenderMan's bilinear patch over (u,v) in [0,1]^2 with corners
// c0 (u0v0), c1 (u1v0), c2 (u0v1), c3 (u1v1):
//     f(u,v) = (1-u)(1-v) f0 + u(1-v) f1 + (1-u)v f2 + uv f3
// for P, the vertex normals and st alike. A convex planar quad face a b c d is the piece
// (a, b, d, c). A triangle a b c is the same patch with the edge v = 1 collapsed onto c:
// corners (a, b, c, c), so its weights (1-u)(1-v), u(1-v), v are barycentric coordinates.
// Why this and not barycentrics (u, v, 1-u-v) over the unit square's lower half: every (u,v) of
// the square is a point of the triangle, so the quadtree of regions needs no clipping to a
// half-square and every number type runs the one bilinear formula that quads use; and the
// weights are linear along every edge (the collapse is at a vertex), so a point of an edge gets
// the same interpolated normal from both faces that share the edge. The price: near v = 1 the
// pieces' regions are thin slivers around c (dPdu -> 0 there), which the bound tree splits along
// the longer parameter anyway.
//
// No cracks. The displacement direction N of a mesh with "N" is the interpolated vertex normal
// (normalised), which along a shared edge depends only on the edge's two vertices and the point:
// both faces then displace the same points along the same normals, and the displaced mesh stays
// closed (up to rounding, which the bounds cover). Without "N", N is the face's geometric normal
// and faces displaced along different normals part at every crease, as in RenderMan.
// u, v are the piece's parameters (RenderMan leaves them undefined on polygons); s, t are the
// user's "st" (or "s", "t") where given, else u, v. Either kind of shader input breaks the
// guarantee above when it differs between faces at an edge (u, v do; facevarying st may).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/geometry/primvar.h"
#include "scene/geometry/quadric.h"
#include "vm/numbers/number.h"
#include "vm/numbers/vec3.h"

namespace affray::renderer {

/// One (u,v) piece of a polygon face: a bilinear quad, or a triangle with corner 3 == corner 2.
struct MeshPiece {
    /// Corners in RenderMan's patch order u0v0, u1v0, u0v1, u1v1 (world space).
    std::array<glm::dvec3, 4> P{};
    /// Vertex normals at the corners (world space, any positive length), if `hasNormals`.
    std::array<glm::dvec3, 4> N{};
    /// s and t at the corners, if `hasST` (else s, t are u, v).
    std::array<glm::dvec2, 4> st{};
    /// The face's unit geometric normal, the Newell normal of its outer loop in vertex order (so
    /// dPdu x dPdv of a piece points the same way): N and Ng without "N", and Ng always.
    glm::dvec3 faceNormal{0, 0, 1};
    bool triangle = false;
    bool hasNormals = false;
    bool hasST = false;
    int face = 0;  ///< The face's index in its mesh, for messages and tests.
    /// The corners' indices among the mesh's face corners (PolygonMesh::corners), where the
    /// caller finds their values of other primitive variables (Cs, Os).
    std::array<int, 4> faceCorner{};
};

/// A primitive variable of a polygon mesh: `components` numbers per value, values by storage
/// class (one; one per face; one per point for Varying and Vertex; one per face corner).
struct MeshVariable {
    StorageClass storage = StorageClass::Vertex;
    int components = 1;
    std::vector<double> values;
};

/// A polygon mesh as RenderMan gives it, already in world space: face f has loops[f] loops (the
/// first its outline, the others holes), loop l has loopSizes[l] corners, and corner c is the
/// point points[corners[c]]. Normals (vertex normals, 3 components; already carried to world
/// space as normals) and st (2), s, t (1) are optional.
struct PolygonMesh {
    std::vector<glm::dvec3> points;
    std::vector<int> loops, loopSizes, corners;
    std::optional<MeshVariable> normals, st, s, t;
};

/// A polygon mesh split into pieces, kept as one object that every piece's primitive shares: the
/// mesh's arrays once, and per piece only the face corners it joins (24 bytes). A piece's
/// corner values (MeshPiece) are gathered from the arrays when it is evaluated (Piece), so a
/// mesh of a million faces is not a million copies of its corners.
struct PieceMesh {
    /// The mesh (world space); its loops and loop sizes are dropped once it is split.
    PolygonMesh mesh;
    /// The face normals (MeshPiece::faceNormal) that a piece's own corners do not give: those of
    /// the faces split into triangles (the normal of the whole outline), and of lone pieces.
    std::vector<glm::dvec3> faceNormals;
    /// A piece: its corners' indices among the mesh's face corners, in patch order (a triangle
    /// repeats its last), its face, and where its face's normal comes from: kOwnNormal for a
    /// face that is the piece alone (the Newell normal of its corners in the face's order, as
    /// the split computed it), else its index in faceNormals.
    struct Corners {
        std::array<int32_t, 4> faceCorner{};
        int32_t face = 0;
        int32_t normal = kOwnNormal;
        bool triangle() const { return faceCorner[3] == faceCorner[2]; }
    };
    static_assert(sizeof(Corners) == 24, "no padding: a mesh's identity hashes its pieces as bytes");
    static constexpr int32_t kOwnNormal = -1;
    std::vector<Corners> pieces;
    /// The mesh's "Cs" (colors[0]) and "Os" (colors[1]) if it varies over it (a constant one is
    /// the primitive's colour).
    std::optional<ColorValues> colors[2];

    /// Calls visit(name, array, form) for every array of the mesh (a std::vector of plain
    /// values; `form` its storage class and components, "none" for a variable it lacks): what
    /// the render's identity hashes and its memory count adds up, so that an array added here
    /// is in both.
    template <class Visit>
    void ForEachArray(Visit&& visit) const {
        visit("points", mesh.points, "");
        visit("corners", mesh.corners, "");
        static const std::vector<double> none;
        auto variable = [&](const char* name, const std::optional<MeshVariable>& v) {
            if (!v) return visit(name, none, "none");
            visit(name, v->values, std::to_string(int(v->storage)) + " " + std::to_string(v->components));
        };
        variable("N", mesh.normals);
        variable("st", mesh.st);
        variable("s", mesh.s);
        variable("t", mesh.t);
        visit("face normals", faceNormals, "");
        visit("pieces", pieces, "");
        static const std::vector<glm::dvec3> noColor;
        for (int k = 0; k < 2; ++k)
            visit(k ? "Os" : "Cs", colors[k] ? colors[k]->values : noColor,
                  colors[k] ? std::to_string(int(colors[k]->storage)) : std::string("none"));
    }

    /// Piece `index` with its corner values, as SplitMesh's vector form gives it.
    MeshPiece Piece(size_t index) const;
    /// The face normal of piece `index` (MeshPiece::faceNormal).
    glm::dvec3 FaceNormal(size_t index) const;
    /// The values of colors[k] at piece `index`'s corners (patch order); false without colors[k].
    /// Shading takes Cs and Os bilinear between them over the piece (so, on a triangle, linear
    /// between the face's vertices, as RenderMan's varying values are).
    bool CornerColors(size_t index, int k, std::array<glm::dvec3, 4>* out) const;
};

/// Splits every face of `mesh` into `out`'s pieces (taking the mesh's arrays); the same as the
/// vector form below, with the same messages.
std::string SplitMesh(PolygonMesh mesh, PieceMesh* out);

/// Splits every face of `mesh` into pieces: a convex planar quad without holes is one quad
/// piece, a triangle is one triangle piece, any other face (concave, more corners, holes) is
/// triangulated by ear clipping in its plane (holes first joined to the outline by bridge edges).
/// Collinear corners are kept as triangle corners (never dropped: a neighbour face has that
/// vertex too, and dropping it would leave a T-junction that a displacement opens). Returns an
/// empty string, or what is wrong ("face 3 is degenerate: its corners are collinear").
/// Assumes the counts are consistent (the RIB reader checks them).
std::string SplitMesh(const PolygonMesh& mesh, std::vector<MeshPiece>* pieces);

/// The one-line description of a piece, for logs and tests.
std::string ToString(const MeshPiece& piece);

namespace mesh_detail {
/// f0 + (f1 - f0) u + (f2 - f0) v + (f0 - f1 - f2 + f3) uv for double corner values, with zero
/// coefficients skipped (a flat axis-aligned face has many: each is work saved in every bound).
template <class T>
T Bilerp(double f0, double f1, double f2, double f3, const T& u, const T& v, const T& uv) {
    const double a = f1 - f0, b = f2 - f0, d = f0 - f1 - f2 + f3;
    T r(f0);
    if (a != 0) r = r + u * a;
    if (b != 0) r = r + v * b;
    if (d != 0) r = r + uv * d;
    return r;
}
}  // namespace mesh_detail

/// The point, tangents and (with vertex normals) normal direction of `piece` at (u, v), in any
/// number type: the bilinear formula of the file head, written once for every T.
template <class T>
SurfaceFrame<T> MeshPieceFrame(const MeshPiece& piece, const T& u, const T& v) {
    using mesh_detail::Bilerp;
    const T uv = u * v;
    SurfaceFrame<T> f;
    for (int i = 0; i < 3; ++i) {
        const auto& p = piece.P;
        f.P[i] = Bilerp(p[0][i], p[1][i], p[2][i], p[3][i], u, v, uv);
        // dP/du = a + d v and dP/dv = b + d u, with P = c0 + a u + b v + d uv.
        const double a = p[1][i] - p[0][i], b = p[2][i] - p[0][i], d = p[0][i] - p[1][i] - p[2][i] + p[3][i];
        f.dPdu[i] = d != 0 ? v * d + a : T(a);
        f.dPdv[i] = d != 0 ? u * d + b : T(b);
        if (piece.hasNormals) {
            const auto& n = piece.N;
            f.normalDirection[i] = Bilerp(n[0][i], n[1][i], n[2][i], n[3][i], u, v, uv);
        }
    }
    f.hasNormalDirection = piece.hasNormals;
    return f;
}

/// s and t of `piece` at (u, v): the interpolated st if it has one, else u and v.
template <class T>
void MeshPieceST(const MeshPiece& piece, const T& u, const T& v, T* s, T* t) {
    if (!piece.hasST) {
        *s = u;
        *t = v;
        return;
    }
    using mesh_detail::Bilerp;
    const T uv = u * v;
    const auto& c = piece.st;
    *s = Bilerp(c[0].x, c[1].x, c[2].x, c[3].x, u, v, uv);
    *t = Bilerp(c[0].y, c[1].y, c[2].y, c[3].y, u, v, uv);
}

}  // namespace affray::renderer
