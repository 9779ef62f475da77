// scene/geometry/mesh.cpp: splitting polygon faces into pieces (scene/geometry/mesh.h).
// Faces that are not a triangle or a convex quad are triangulated by ear clipping in the plane
// the face's Newell normal picks (the coordinate plane it is steepest to), after joining each hole
// to the outline by a bridge: a pair of coincident edges from a hole vertex to a visible vertex
// of the outline, which makes one simple loop (as in Eberly, "Triangulation by Ear Clipping").
#include "scene/geometry/mesh.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace affray::renderer {

namespace {

/// A corner of a face: the point it uses and its index among all face corners of the mesh
/// (where facevarying values are).
struct Corner {
    int point = 0;
    int faceCorner = 0;
};

/// The term of Newell's normal for the edge a -> b.
glm::dvec3 NewellTerm(const glm::dvec3& a, const glm::dvec3& b) {
    return glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
}

/// Newell's normal of a loop: twice its vector area, robust for non-convex and slightly
/// non-planar loops.
glm::dvec3 NewellNormal(const PolygonMesh& mesh, const std::vector<Corner>& loop) {
    glm::dvec3 n(0.0);
    for (size_t i = 0; i < loop.size(); ++i) {
        n += NewellTerm(mesh.points[loop[i].point], mesh.points[loop[(i + 1) % loop.size()].point]);
    }
    return n;
}

/// Component k of `var`'s value at a corner of face `face`.
double Fetch(const MeshVariable& var, int face, const Corner& c, int k) {
    size_t index = 0;
    switch (var.storage) {
        case StorageClass::Constant: index = 0; break;
        case StorageClass::Uniform: index = static_cast<size_t>(face); break;
        case StorageClass::Varying:
        case StorageClass::Vertex: index = static_cast<size_t>(c.point); break;
        case StorageClass::FaceVarying: index = static_cast<size_t>(c.faceCorner); break;
    }
    return var.values[index * static_cast<size_t>(var.components) + static_cast<size_t>(k)];
}

/// The piece of `face` with corners `c` in patch order (a triangle repeats its last corner).
MeshPiece MakePiece(const PolygonMesh& mesh, int face, const glm::dvec3& normal, const std::array<Corner, 4>& c,
                    bool triangle) {
    MeshPiece piece;
    piece.face = face;
    piece.triangle = triangle;
    piece.faceNormal = normal;
    piece.hasNormals = mesh.normals.has_value();
    piece.hasST = mesh.st || mesh.s || mesh.t;
    for (int i = 0; i < 4; ++i) {
        piece.P[i] = mesh.points[static_cast<size_t>(c[i].point)];
        piece.faceCorner[i] = c[i].faceCorner;
        if (mesh.normals)
            for (int k = 0; k < 3; ++k) piece.N[i][k] = Fetch(*mesh.normals, face, c[i], k);
        if (!piece.hasST) continue;
        // "st" wins over "s" and "t"; a missing one of s, t is the piece's own parameter (u or
        // v at the corner: the bilinear form of the corners' (u, v) is (u, v)).
        piece.st[i] = glm::dvec2(i & 1, i >> 1);
        if (mesh.st) {
            piece.st[i] = glm::dvec2(Fetch(*mesh.st, face, c[i], 0), Fetch(*mesh.st, face, c[i], 1));
            continue;
        }
        if (mesh.s) piece.st[i].x = Fetch(*mesh.s, face, c[i], 0);
        if (mesh.t) piece.st[i].y = Fetch(*mesh.t, face, c[i], 0);
    }
    return piece;
}

double Orient(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// Whether Orient(a, b, c) is zero up to rounding, relative to the lengths involved.
bool CollinearP(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return std::fabs(Orient(a, b, c)) <= 1e-12 * glm::length(b - a) * glm::length(c - a);
}

/// Whether p is inside triangle abc (counter-clockwise) or on its boundary, up to rounding.
bool InsideOrOnP(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& p) {
    auto side = [&](const glm::dvec2& x, const glm::dvec2& y) { return Orient(x, y, p) >= 0 || CollinearP(x, y, p); };
    return side(a, b) && side(b, c) && side(c, a);
}

/// Whether segments pq and rs cross at a point inside both (touching at an end does not count).
bool ProperCrossP(const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r, const glm::dvec2& s) {
    const double d1 = Orient(p, q, r), d2 = Orient(p, q, s), d3 = Orient(r, s, p), d4 = Orient(r, s, q);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

/// Whether direction w leaves vertex b (with neighbours a before, c after, interior on the left)
/// into the interior.
bool IntoInteriorP(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& w) {
    const glm::dvec2 toNext = c - b, toPrev = a - b;
    auto cross = [](const glm::dvec2& x, const glm::dvec2& y) { return x.x * y.y - x.y * y.x; };
    if (Orient(a, b, c) >= 0) return cross(toNext, w) > 0 && cross(w, toPrev) > 0;  // convex: inside the wedge
    return !(cross(toPrev, w) >= 0 && cross(w, toNext) >= 0);                       // reflex: outside the notch
}

/// A face's corners in its plane.
struct Loop2 {
    std::vector<Corner> corners;
    std::vector<glm::dvec2> xy;
};

double Area(const Loop2& loop) {
    double a = 0;
    for (size_t i = 0; i < loop.xy.size(); ++i) {
        const glm::dvec2 &p = loop.xy[i], &q = loop.xy[(i + 1) % loop.xy.size()];
        a += p.x * q.y - p.y * q.x;
    }
    return 0.5 * a;
}

/// Joins `hole` (clockwise) into `outline` (counter-clockwise) by a bridge from the hole's
/// rightmost vertex to the nearest outline vertex it sees; false if there is none.
bool Bridge(Loop2& outline, const Loop2& hole, const std::vector<Loop2>& others) {
    const size_t m = static_cast<size_t>(
        std::max_element(hole.xy.begin(), hole.xy.end(), [](auto& a, auto& b) { return a.x < b.x; }) - hole.xy.begin());
    const glm::dvec2 M = hole.xy[m];
    std::vector<size_t> order(outline.xy.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return glm::length(outline.xy[a] - M) < glm::length(outline.xy[b] - M); });
    auto blocked = [&](const Loop2& loop, const glm::dvec2& V) {
        for (size_t i = 0; i < loop.xy.size(); ++i)
            if (ProperCrossP(M, V, loop.xy[i], loop.xy[(i + 1) % loop.xy.size()])) return true;
        return false;
    };
    const size_t n = outline.xy.size(), h = hole.xy.size();
    for (size_t iv : order) {
        const glm::dvec2 V = outline.xy[iv];
        if (V == M) continue;
        if (!IntoInteriorP(outline.xy[(iv + n - 1) % n], V, outline.xy[(iv + 1) % n], M - V)) continue;
        if (!IntoInteriorP(hole.xy[(m + h - 1) % h], M, hole.xy[(m + 1) % h], V - M)) continue;
        if (blocked(outline, V) || blocked(hole, V)) continue;
        if (std::any_of(others.begin(), others.end(), [&](const Loop2& o) { return blocked(o, V); })) continue;
        // outline[..iv], hole from m all the way round to m, then V again, outline[iv+1..].
        Loop2 merged;
        for (size_t i = 0; i <= iv; ++i)
            merged.corners.push_back(outline.corners[i]), merged.xy.push_back(outline.xy[i]);
        for (size_t k = 0; k <= h; ++k)
            merged.corners.push_back(hole.corners[(m + k) % h]), merged.xy.push_back(hole.xy[(m + k) % h]);
        merged.corners.push_back(outline.corners[iv]), merged.xy.push_back(V);
        for (size_t i = iv + 1; i < n; ++i)
            merged.corners.push_back(outline.corners[i]), merged.xy.push_back(outline.xy[i]);
        outline = std::move(merged);
        return true;
    }
    return false;
}

/// Ear clipping of a simple counter-clockwise loop (bridges allowed): appends triangles as
/// corner triples. An ear's tip must be strictly convex and its triangle hold no other corner,
/// not even on its boundary, so collinear corners end up as corners of triangles, never inside
/// an edge. False if no ear is left (a self-intersecting loop).
bool ClipEars(const Loop2& loop, std::vector<std::array<Corner, 3>>* triangles) {
    std::vector<size_t> left(loop.xy.size());
    for (size_t i = 0; i < left.size(); ++i) left[i] = i;
    while (left.size() > 3) {
        const size_t n = left.size();
        bool clipped = false;
        for (size_t i = 0; i < n && !clipped; ++i) {
            const size_t ia = left[(i + n - 1) % n], ib = left[i], ic = left[(i + 1) % n];
            const glm::dvec2 &a = loop.xy[ia], &b = loop.xy[ib], &c = loop.xy[ic];
            if (Orient(a, b, c) <= 0 || CollinearP(a, b, c)) continue;
            bool empty = true;
            for (size_t j : left) {
                const glm::dvec2& p = loop.xy[j];
                if (p == a || p == b || p == c) continue;  // the ear's own corners and their bridge twins
                if (InsideOrOnP(a, b, c, p)) {
                    empty = false;
                    break;
                }
            }
            if (!empty) continue;
            triangles->push_back({loop.corners[ia], loop.corners[ib], loop.corners[ic]});
            left.erase(left.begin() + static_cast<std::ptrdiff_t>(i));
            clipped = true;
        }
        if (!clipped) return false;
    }
    // The last three: a zero-area remainder (collinear corners) covers nothing.
    const glm::dvec2 &a = loop.xy[left[0]], &b = loop.xy[left[1]], &c = loop.xy[left[2]];
    if (Orient(a, b, c) > 0 && !CollinearP(a, b, c))
        triangles->push_back({loop.corners[left[0]], loop.corners[left[1]], loop.corners[left[2]]});
    return true;
}

/// Whether the quad abcd turns the same way as `normal` at every corner (so the bilinear piece
/// over it does not fold).
bool ConvexQuadP(const std::array<glm::dvec3, 4>& p, const glm::dvec3& normal) {
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 turn = glm::cross(p[(i + 1) % 4] - p[i], p[(i + 2) % 4] - p[(i + 1) % 4]);
        if (!(glm::dot(turn, normal) > 1e-12 * glm::length(turn))) return false;
    }
    return true;
}

}  // namespace

MeshPiece PieceMesh::Piece(size_t index) const {
    const Corners& p = pieces[index];
    std::array<Corner, 4> c;
    for (int i = 0; i < 4; ++i) c[i] = {mesh.corners[static_cast<size_t>(p.faceCorner[i])], p.faceCorner[i]};
    return MakePiece(mesh, p.face, FaceNormal(index), c, p.triangle());
}

glm::dvec3 PieceMesh::FaceNormal(size_t index) const {
    const Corners& p = pieces[index];
    if (p.normal != kOwnNormal) return faceNormals[static_cast<size_t>(p.normal)];
    // The face's outline in its own order: a triangle's corners, a quad's 0 1 3 2 (patch order
    // swaps the last two); the same sums as SplitMesh's, so the same bits.
    const bool triangle = p.triangle();
    const int order[4] = {0, 1, triangle ? 2 : 3, 2}, n = triangle ? 3 : 4;
    glm::dvec3 newell(0.0);
    for (int i = 0; i < n; ++i) {
        auto point = [&](int k) { return mesh.points[size_t(mesh.corners[size_t(p.faceCorner[order[k]])])]; };
        const glm::dvec3 a = point(i), b = point((i + 1) % n);
        newell += NewellTerm(a, b);
    }
    return newell / glm::length(newell);
}

bool PieceMesh::CornerColors(size_t index, int k, std::array<glm::dvec3, 4>* out) const {
    const std::optional<ColorValues>& color = colors[k];
    if (!color) return false;
    const Corners& piece = pieces[index];
    for (int i = 0; i < 4; ++i) {
        const size_t c = static_cast<size_t>(piece.faceCorner[i]);
        switch (color->storage) {
            case StorageClass::Constant: (*out)[i] = color->values[0]; break;
            case StorageClass::Uniform: (*out)[i] = color->values[size_t(piece.face)]; break;
            case StorageClass::Varying:
            case StorageClass::Vertex: (*out)[i] = color->values[size_t(mesh.corners[c])]; break;
            case StorageClass::FaceVarying: (*out)[i] = color->values[c]; break;
        }
    }
    return true;
}

std::string SplitMesh(PolygonMesh polygons, PieceMesh* out) {
    out->mesh = std::move(polygons);
    const PolygonMesh& mesh = out->mesh;
    out->faceNormals.clear();
    out->pieces.clear();
    out->pieces.reserve(mesh.loops.size());
    // A face that is one piece finds its normal from its corners; the pieces of a triangulated
    // face share the one stored.
    auto add = [&](int face, const std::array<Corner, 4>& c, int32_t normal) {
        out->pieces.push_back({{c[0].faceCorner, c[1].faceCorner, c[2].faceCorner, c[3].faceCorner}, face, normal});
    };
    size_t loopIndex = 0, cornerIndex = 0;
    for (size_t f = 0; f < mesh.loops.size(); ++f) {
        const int face = static_cast<int>(f);
        const std::string name = "face " + std::to_string(f);
        std::vector<std::vector<Corner>> loops(static_cast<size_t>(mesh.loops[f]));
        for (std::vector<Corner>& loop : loops) {
            for (int k = 0; k < mesh.loopSizes[loopIndex]; ++k, ++cornerIndex)
                loop.push_back({mesh.corners[cornerIndex], static_cast<int>(cornerIndex)});
            ++loopIndex;
        }
        if (loops.empty() || loops[0].size() < 3) return name + " has fewer than 3 corners";
        const glm::dvec3 newell = NewellNormal(mesh, loops[0]);
        const double length = glm::length(newell);
        if (!(length > 0) || !std::isfinite(length))
            return name + " is degenerate: its outline has no area (its corners are collinear or coincide)";
        const glm::dvec3 normal = newell / length;
        auto point = [&](const Corner& c) { return mesh.points[c.point]; };
        // A triangle, or a convex quad without holes: one piece.
        if (loops.size() == 1 && loops[0].size() == 3) {
            const auto& l = loops[0];
            add(face, {l[0], l[1], l[2], l[2]}, PieceMesh::kOwnNormal);
            continue;
        }
        if (loops.size() == 1 && loops[0].size() == 4) {
            const auto& l = loops[0];
            if (ConvexQuadP({point(l[0]), point(l[1]), point(l[2]), point(l[3])}, normal)) {
                add(face, {l[0], l[1], l[3], l[2]}, PieceMesh::kOwnNormal);
                continue;
            }
        }
        // Project to the coordinate plane the normal is steepest to, keeping the outline
        // counter-clockwise: (x, y) of the two other axes, swapped if the normal's component is
        // negative.
        const glm::dvec3 an = glm::abs(normal);
        const int drop = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
        const int ax = (drop + 1) % 3, ay = (drop + 2) % 3;
        const bool swap = normal[drop] < 0;
        std::vector<Loop2> flat(loops.size());
        for (size_t l = 0; l < loops.size(); ++l) {
            if (loops[l].size() < 3) return name + " has a hole with fewer than 3 corners";
            for (const Corner& c : loops[l]) {
                const glm::dvec3 p = point(c);
                flat[l].corners.push_back(c);
                flat[l].xy.push_back(swap ? glm::dvec2(p[ay], p[ax]) : glm::dvec2(p[ax], p[ay]));
            }
            // The outline counter-clockwise (it is, by the normal), holes clockwise.
            if (l > 0 && Area(flat[l]) > 0) {
                std::reverse(flat[l].corners.begin(), flat[l].corners.end());
                std::reverse(flat[l].xy.begin(), flat[l].xy.end());
            }
        }
        // Holes by decreasing rightmost x, so each bridge is found before a later hole's.
        Loop2 outline = flat[0];
        std::vector<Loop2> holes(flat.begin() + 1, flat.end());
        auto maxX = [](const Loop2& l) {
            double x = -INFINITY;
            for (const glm::dvec2& p : l.xy) x = std::max(x, p.x);
            return x;
        };
        std::sort(holes.begin(), holes.end(), [&](const Loop2& a, const Loop2& b) { return maxX(a) > maxX(b); });
        for (size_t h = 0; h < holes.size(); ++h) {
            const std::vector<Loop2> others(holes.begin() + static_cast<std::ptrdiff_t>(h) + 1, holes.end());
            if (!Bridge(outline, holes[h], others))
                return name + " cannot be triangulated: a hole is not inside its outline (or loops cross)";
        }
        std::vector<std::array<Corner, 3>> triangles;
        if (!ClipEars(outline, &triangles) || triangles.empty())
            return name + " cannot be triangulated: its loops intersect themselves or each other";
        const auto stored = static_cast<int32_t>(out->faceNormals.size());
        out->faceNormals.push_back(normal);
        for (const auto& t : triangles) add(face, {t[0], t[1], t[2], t[2]}, stored);
    }
    // Splitting is done: a piece needs only the face corners' points and values.
    out->mesh.loops = {};
    out->mesh.loopSizes = {};
    out->mesh.corners.shrink_to_fit();
    out->pieces.shrink_to_fit();
    out->faceNormals.shrink_to_fit();
    return "";
}

std::string SplitMesh(const PolygonMesh& mesh, std::vector<MeshPiece>* pieces) {
    PieceMesh split;
    std::string problem = SplitMesh(mesh, &split);
    for (size_t i = 0; i < split.pieces.size(); ++i) pieces->push_back(split.Piece(i));
    return problem;
}

std::string ToString(const MeshPiece& piece) {
    std::ostringstream out;
    out << (piece.triangle ? "triangle" : "quad") << " of face " << piece.face << ":";
    for (int i = 0; i < (piece.triangle ? 3 : 4); ++i)
        out << " [" << piece.P[i].x << ' ' << piece.P[i].y << ' ' << piece.P[i].z << ']';
    if (piece.hasNormals) out << " N";
    if (piece.hasST) out << " st";
    return out.str();
}

}  // namespace affray::renderer
