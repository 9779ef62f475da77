// scene/geometry/subdivision.cpp: Catmull-Clark refinement with RenderMan's tags and the patches
// of the refined mesh (scene/geometry/subdivision.h: the file head there gives the rules).
// Layout: the topology of one level (half-edges are face corners), one refinement step, the
// per-vertex limit data (positions and Bezier edge points), then the faces' Bezier nets, the
// shared edge normal curves and the patches. Longer than 600 lines because every step works on
// the same private half-edge types (Level, Topology, Ring); split it by step if it grows.
#include "scene/geometry/subdivision.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace affray::renderer {

namespace {

constexpr double kInfiniteSharpness = 1e30;

/// A primitive variable refined with the mesh (st, then the mesh's other variables): values per
/// vertex (the vertex class, refined as P is) or per face corner (the others: bilinear in each
/// face, its children's corners interpolated from its own).
struct VariableData {
    bool perVertex = false;
    std::vector<glm::dvec3> values;
};

/// One level of the mesh: faces as corner lists, tags per edge and vertex, and the data refined
/// with it (points and primitive variables).
struct Level {
    std::vector<glm::dvec3> P;
    std::vector<VariableData> data;
    std::vector<int> start, verts;  // face f: verts[start[f] .. start[f + 1])
    std::vector<char> hole;
    std::vector<char> corner;                     // per vertex: a sharp corner
    std::map<std::pair<int, int>, double> sharp;  // undirected edge (sorted) -> sharpness > 0
    int Faces() const { return static_cast<int>(start.size()) - 1; }
    int Size(int f) const { return start[f + 1] - start[f]; }
};

/// The half-edge structure of a level: half-edge h is face corner h, from verts[h] to the next
/// corner's vertex.
struct Topology {
    const Level* level = nullptr;
    std::vector<int> faceOf, twin, edgeOf;
    std::vector<std::array<int, 2>> edgeVerts, edgeHalf;  // edge: its vertices and half-edges (or -1)
    std::vector<double> edgeSharp;                        // boundary edges infinitely sharp
    std::vector<int> firstOut;                            // per vertex: an out half-edge, boundary first
    std::vector<char> boundaryVertex;

    int Next(int h) const {
        const int f = faceOf[h];
        return h + 1 == level->start[f + 1] ? level->start[f] : h + 1;
    }
    int Prev(int h) const {
        const int f = faceOf[h];
        return h == level->start[f] ? level->start[f + 1] - 1 : h - 1;
    }
    int Src(int h) const { return level->verts[h]; }
    int Dst(int h) const { return level->verts[Next(h)]; }
};

/// The faces around a vertex in order: out half-edges h[j] (to neighbour m[j], in face f[j]
/// between m[j] and m[j + 1]); a boundary vertex has one more neighbour than faces.
struct Ring {
    std::vector<int> h, m, e;  // e: edge ids of v -> m[j]
    bool boundary = false;
    int Valence() const { return static_cast<int>(m.size()); }
    int FaceCount() const { return static_cast<int>(h.size()); }
};

std::string EdgeName(int a, int b) { return std::to_string(a) + "-" + std::to_string(b); }

std::string BuildTopology(const Level& level, Topology* t) {
    t->level = &level;
    const int nH = static_cast<int>(level.verts.size());
    const int nV = static_cast<int>(level.P.size());
    t->faceOf.assign(nH, 0);
    for (int f = 0; f < level.Faces(); ++f)
        for (int h = level.start[f]; h < level.start[f + 1]; ++h) t->faceOf[h] = f;
    std::map<std::pair<int, int>, int> directed;
    for (int h = 0; h < nH; ++h) {
        const int a = t->Src(h), b = t->Dst(h);
        if (a == b)
            return "face " + std::to_string(t->faceOf[h]) + " uses vertex " + std::to_string(a) + " twice in a row";
        if (!directed.emplace(std::pair{a, b}, h).second)
            return "edge " + EdgeName(a, b) +
                   " is used twice in the same direction (a non-manifold edge, or faces of opposite orientation)";
    }
    t->twin.assign(nH, -1);
    t->edgeOf.assign(nH, -1);
    for (int h = 0; h < nH; ++h) {
        if (auto it = directed.find({t->Dst(h), t->Src(h)}); it != directed.end()) t->twin[h] = it->second;
        if (t->edgeOf[h] >= 0) continue;
        const int e = static_cast<int>(t->edgeVerts.size());
        t->edgeVerts.push_back({t->Src(h), t->Dst(h)});
        t->edgeHalf.push_back({h, t->twin[h]});
        t->edgeOf[h] = e;
        if (t->twin[h] >= 0) t->edgeOf[t->twin[h]] = e;
        double s = t->twin[h] < 0 ? kInfiniteSharpness : 0;
        if (auto it = level.sharp.find(std::minmax(t->Src(h), t->Dst(h))); it != level.sharp.end())
            s = std::max(s, it->second);
        t->edgeSharp.push_back(s);
    }
    // Each vertex's fan: start at the out half-edge with no twin (the boundary), if any.
    t->firstOut.assign(nV, -1);
    t->boundaryVertex.assign(nV, 0);
    std::vector<int> outCount(nV, 0);
    for (int h = 0; h < nH; ++h) {
        const int v = t->Src(h);
        ++outCount[v];
        if (t->twin[h] < 0) {
            if (t->boundaryVertex[v]) return "vertex " + std::to_string(v) + " joins two separate fans of faces";
            t->boundaryVertex[v] = 1;
            t->firstOut[v] = h;
        } else if (t->firstOut[v] < 0) {
            t->firstOut[v] = h;
        }
    }
    // Every out half-edge of a vertex must be in its one fan.
    for (int v = 0; v < nV; ++v) {
        if (t->firstOut[v] < 0) continue;
        int count = 0;
        for (int h = t->firstOut[v];;) {
            ++count;
            const int back = t->twin[t->Prev(h)];
            if (back < 0 || back == t->firstOut[v] || count > outCount[v]) break;
            h = back;
        }
        if (count != outCount[v]) return "vertex " + std::to_string(v) + " joins two separate fans of faces";
    }
    return "";
}

Ring RingOf(const Topology& t, int v) {
    Ring r;
    const int first = t.firstOut[v];
    if (first < 0) return r;
    r.boundary = t.boundaryVertex[v] != 0;
    for (int h = first;;) {
        r.h.push_back(h);
        r.m.push_back(t.Dst(h));
        r.e.push_back(t.edgeOf[h]);
        const int in = t.Prev(h);
        const int back = t.twin[in];
        if (back < 0) {
            // The boundary's last edge comes in to v: its source is the last neighbour.
            r.m.push_back(t.Src(in));
            r.e.push_back(t.edgeOf[in]);
            break;
        }
        if (back == first) break;
        h = back;
    }
    return r;
}

/// The refinement rules of the file head for one kind of vertex data.
std::vector<glm::dvec3> RefineData(const Topology& t, const std::vector<glm::dvec3>& x) {
    const Level& level = *t.level;
    const int nV = static_cast<int>(x.size()), nE = static_cast<int>(t.edgeVerts.size()), nF = level.Faces();
    std::vector<glm::dvec3> out(static_cast<size_t>(nV + nE + nF));
    std::vector<glm::dvec3> facePoint(nF);
    for (int f = 0; f < nF; ++f) {
        glm::dvec3 sum(0.0);
        for (int h = level.start[f]; h < level.start[f + 1]; ++h) sum += x[level.verts[h]];
        facePoint[f] = sum / double(level.Size(f));
        out[nV + nE + f] = facePoint[f];
    }
    for (int e = 0; e < nE; ++e) {
        const auto [a, b] = t.edgeVerts[e];
        const glm::dvec3 mid = 0.5 * (x[a] + x[b]);
        const double s = t.edgeSharp[e];
        glm::dvec3 p = mid;
        if (s < 1) {
            const glm::dvec3 smooth =
                0.25 * (x[a] + x[b] + facePoint[t.faceOf[t.edgeHalf[e][0]]] + facePoint[t.faceOf[t.edgeHalf[e][1]]]);
            p = s > 0 ? smooth + s * (mid - smooth) : smooth;
        }
        out[nV + e] = p;
    }
    for (int v = 0; v < nV; ++v) {
        const Ring r = RingOf(t, v);
        if (r.m.empty()) {
            out[v] = x[v];
            continue;
        }
        std::vector<int> sharpNeighbours;
        double sharpSum = 0;
        for (size_t j = 0; j < r.e.size(); ++j)
            if (t.edgeSharp[r.e[j]] > 0) {
                sharpNeighbours.push_back(r.m[j]);
                sharpSum += std::min(t.edgeSharp[r.e[j]], 1.0);
            }
        if (level.corner[v] || sharpNeighbours.size() >= 3) {
            out[v] = x[v];
            continue;
        }
        glm::dvec3 smooth = x[v];
        if (!r.boundary) {
            const double n = r.Valence();
            glm::dvec3 q(0.0), edgeMid(0.0);
            for (int j = 0; j < r.Valence(); ++j) {
                q += facePoint[t.faceOf[r.h[j]]];
                edgeMid += 0.5 * (x[v] + x[r.m[j]]);
            }
            smooth = (q / n + 2.0 * edgeMid / n + (n - 3) * x[v]) / n;
        }
        if (sharpNeighbours.size() == 2) {
            const glm::dvec3 crease = (x[sharpNeighbours[0]] + 6.0 * x[v] + x[sharpNeighbours[1]]) / 8.0;
            const double blend = r.boundary ? 1.0 : sharpSum / 2;
            out[v] = blend >= 1 ? crease : smooth + blend * (crease - smooth);
        } else {
            out[v] = smooth;
        }
    }
    return out;
}

/// One Catmull-Clark step of `level` (topology `t`): new vertices are the old ones, then one per
/// edge, then one per face; face f's corner i becomes the quad (v_i, edge i, face, edge i - 1).
Level Refine(const Topology& t) {
    const Level& level = *t.level;
    const int nV = static_cast<int>(level.P.size()), nE = static_cast<int>(t.edgeVerts.size());
    Level next;
    next.P = RefineData(t, level.P);
    next.data.resize(level.data.size());
    for (size_t k = 0; k < level.data.size(); ++k) {
        next.data[k].perVertex = level.data[k].perVertex;
        if (level.data[k].perVertex) next.data[k].values = RefineData(t, level.data[k].values);
    }
    next.corner = level.corner;
    next.corner.resize(next.P.size(), 0);
    next.start.push_back(0);
    for (int f = 0; f < level.Faces(); ++f) {
        const int n = level.Size(f);
        std::vector<glm::dvec3> mean(level.data.size(), glm::dvec3(0.0));
        for (size_t k = 0; k < level.data.size(); ++k)
            if (!level.data[k].perVertex)
                for (int h = level.start[f]; h < level.start[f + 1]; ++h)
                    mean[k] += level.data[k].values[h] / double(n);
        for (int h = level.start[f]; h < level.start[f + 1]; ++h) {
            const int prev = t.Prev(h), nextH = t.Next(h);
            next.verts.insert(next.verts.end(), {level.verts[h], nV + t.edgeOf[h], nV + nE + f, nV + t.edgeOf[prev]});
            next.start.push_back(static_cast<int>(next.verts.size()));
            next.hole.push_back(level.hole[f]);
            for (size_t k = 0; k < level.data.size(); ++k) {
                if (level.data[k].perVertex) continue;
                const std::vector<glm::dvec3>& x = level.data[k].values;
                const glm::dvec3 &s = x[h], &sNext = x[nextH], &sPrev = x[prev];
                next.data[k].values.insert(next.data[k].values.end(),
                                           {s, 0.5 * (s + sNext), mean[k], 0.5 * (s + sPrev)});
            }
        }
    }
    // Children of a sharp edge are one less sharp.
    for (int e = 0; e < nE; ++e) {
        const double s = level.sharp.count(std::minmax(t.edgeVerts[e][0], t.edgeVerts[e][1]))
                             ? level.sharp.at(std::minmax(t.edgeVerts[e][0], t.edgeVerts[e][1]))
                             : 0.0;
        if (s <= 1) continue;
        const double child = s >= kInfiniteSharpness ? s : s - 1;
        next.sharp[std::minmax(t.edgeVerts[e][0], nV + e)] = child;
        next.sharp[std::minmax(t.edgeVerts[e][1], nV + e)] = child;
    }
    return next;
}

/// What a vertex is for the patches: smooth (the Catmull-Clark limit stencils), a crease (two
/// sharp edges) or a corner.
enum class VertexKind { Smooth, Crease, Corner };

/// The limit data of one kind of vertex data over a level: limit positions and, per edge and
/// end, the Bezier point next to that end.
struct LimitData {
    std::vector<glm::dvec3> limit;
    std::vector<std::array<glm::dvec3, 2>> edgePoint;
};

struct VertexInfo {
    VertexKind kind = VertexKind::Smooth;
    Ring ring;
    bool regular = false;  // smooth, interior, valence 4, no sharp edge
};

std::vector<VertexInfo> ClassifyVertices(const Topology& t) {
    const Level& level = *t.level;
    std::vector<VertexInfo> info(level.P.size());
    for (size_t v = 0; v < info.size(); ++v) {
        VertexInfo& vi = info[v];
        vi.ring = RingOf(t, static_cast<int>(v));
        int nSharp = 0;
        for (int e : vi.ring.e) nSharp += t.edgeSharp[e] > 0;
        if (level.corner[v] || nSharp >= 3 || (!vi.ring.boundary && vi.ring.Valence() < 3))
            vi.kind = VertexKind::Corner;
        else if (nSharp == 2)
            vi.kind = VertexKind::Crease;
        vi.regular = vi.kind == VertexKind::Smooth && nSharp == 0 && !vi.ring.boundary && vi.ring.Valence() == 4;
    }
    return info;
}

/// The vertex opposite the out half-edge h's source in its (quad) face.
int Diagonal(const Topology& t, int h) { return t.Dst(t.Next(h)); }

LimitData ComputeLimits(const Topology& t, const std::vector<VertexInfo>& info, const std::vector<glm::dvec3>& x) {
    LimitData d;
    d.limit.assign(x.size(), glm::dvec3(0.0));
    d.edgePoint.assign(t.edgeVerts.size(), {glm::dvec3(0.0), glm::dvec3(0.0)});
    auto setEdgePoint = [&](int e, int v, const glm::dvec3& p) { d.edgePoint[e][t.edgeVerts[e][0] == v ? 0 : 1] = p; };
    for (size_t vi = 0; vi < x.size(); ++vi) {
        const int v = static_cast<int>(vi);
        const Ring& r = info[v].ring;
        if (r.m.empty()) {
            d.limit[v] = x[v];
            continue;
        }
        const int n = r.Valence();
        switch (info[v].kind) {
            case VertexKind::Corner:
                d.limit[v] = x[v];
                for (int j = 0; j < n; ++j) setEdgePoint(r.e[j], v, (2.0 * x[v] + x[r.m[j]]) / 3.0);
                break;
            case VertexKind::Crease: {
                std::vector<int> sharpJ;
                for (int j = 0; j < n; ++j)
                    if (t.edgeSharp[r.e[j]] > 0) sharpJ.push_back(j);
                const glm::dvec3 lim = (x[r.m[sharpJ[0]]] + 4.0 * x[v] + x[r.m[sharpJ[1]]]) / 6.0;
                d.limit[v] = lim;
                const int faces = r.FaceCount();
                for (int j = 0; j < n; ++j) {
                    if (t.edgeSharp[r.e[j]] > 0) {
                        setEdgePoint(r.e[j], v, (2.0 * x[v] + x[r.m[j]]) / 3.0);
                        continue;
                    }
                    // A smooth edge of a crease vertex has a face on each side: the regular
                    // boundary B-spline's point (2/3) L + (d- + 4 m + d+) / 18.
                    const int before = (j - 1 + faces) % faces, after = j % faces;
                    const glm::dvec3 across =
                        (x[Diagonal(t, r.h[before])] + 4.0 * x[r.m[j]] + x[Diagonal(t, r.h[after])]) / 18.0;
                    setEdgePoint(r.e[j], v, 2.0 / 3.0 * lim + across);
                }
                break;
            }
            case VertexKind::Smooth: {
                // Catmull-Clark's limit position and the tangent masks of Halstead, Kass and
                // DeRose 1993 along each edge, scaled so that valence 4 gives the B-spline's
                // Bezier points (Loop and Schaefer 2008).
                const double nd = n;
                glm::dvec3 sumM(0.0), sumD(0.0);
                for (int j = 0; j < n; ++j) {
                    sumM += x[r.m[j]];
                    sumD += x[Diagonal(t, r.h[j])];
                }
                const glm::dvec3 lim = (nd * nd * x[v] + 4.0 * sumM + sumD) / (nd * (nd + 5));
                d.limit[v] = lim;
                const double c = std::cos(2 * M_PI / nd);
                const double a = 1 + c + std::cos(M_PI / nd) * std::sqrt(2 * (9 + c));
                for (int i = 0; i < n; ++i) {
                    glm::dvec3 tangent(0.0);
                    for (int j = 0; j < n; ++j) {
                        const double c0 = std::cos(2 * M_PI * (j - i) / nd), c1 = std::cos(2 * M_PI * (j - i + 1) / nd);
                        tangent += a * c0 * x[r.m[j]] + (c0 + c1) * x[Diagonal(t, r.h[j])];
                    }
                    setEdgePoint(r.e[i], v, lim + tangent / (nd * (nd + 5)));
                }
                break;
            }
        }
    }
    return d;
}

/// A face's Bezier net, index 4 b + a for u index a and v index b (BicubicPatch's order).
using Net = std::array<glm::dvec3, 16>;

/// Where corner k of a quad sits in the 4 x 4 net and the directions of its two edges (x along
/// edge k, y along edge k - 1 reversed).
struct CornerFrame {
    int a, b, xa, xb, ya, yb;
};
constexpr CornerFrame kCorners[4] = {
    {0, 0, 1, 0, 0, 1}, {3, 0, 0, 1, -1, 0}, {3, 3, -1, 0, 0, -1}, {0, 3, 0, -1, 1, 0}};

int NetIndex(int a, int b) { return 4 * b + a; }

Net BezierNet(const Topology& t, const std::vector<VertexInfo>& info, const LimitData& d,
              const std::vector<glm::dvec3>& x, int f) {
    Net net{};
    const int h0 = t.level->start[f];
    for (int k = 0; k < 4; ++k) {
        const int h = h0 + k, hPrev = h0 + (k + 3) % 4;
        const int v = t.Src(h);
        const CornerFrame& c = kCorners[k];
        auto end = [&](int e) { return t.edgeVerts[e][0] == v ? 0 : 1; };
        net[NetIndex(c.a, c.b)] = d.limit[v];
        net[NetIndex(c.a + c.xa, c.b + c.xb)] = d.edgePoint[t.edgeOf[h]][end(t.edgeOf[h])];
        net[NetIndex(c.a + c.ya, c.b + c.yb)] = d.edgePoint[t.edgeOf[hPrev]][end(t.edgeOf[hPrev])];
        // The interior point: the face-corner average of ACC (valence 4 weights at features).
        const bool smooth = info[v].kind == VertexKind::Smooth;
        const double n = smooth ? info[v].ring.Valence() : 4;
        const glm::dvec3 inner = (n * x[v] + 2.0 * (x[t.Dst(h)] + x[t.Src(hPrev)]) + x[Diagonal(t, h)]) / (n + 5);
        net[NetIndex(c.a + c.xa + c.ya, c.b + c.xb + c.yb)] = inner;
    }
    return net;
}

/// The 16 B-spline control points of a regular face (every corner regular), same indexing.
Net BSplineGrid(const Topology& t, const std::vector<VertexInfo>& info, const std::vector<glm::dvec3>& x, int f) {
    Net grid{};
    const int h0 = t.level->start[f];
    for (int k = 0; k < 4; ++k) {
        const int v = t.Src(h0 + k);
        const CornerFrame& c = kCorners[k];
        const int a = c.a == 0 ? 1 : 2, b = c.b == 0 ? 1 : 2;
        // The ring from this face's out half-edge: m = +x, +y, -x, -y; diagonals between them.
        const Ring& r = info[v].ring;
        const int start = static_cast<int>(std::find(r.h.begin(), r.h.end(), h0 + k) - r.h.begin());
        const int dirs[4][2] = {{c.xa, c.xb}, {c.ya, c.yb}, {-c.xa, -c.xb}, {-c.ya, -c.yb}};
        grid[NetIndex(a, b)] = x[v];
        for (int j = 0; j < 4; ++j) {
            const int jj = (start + j) % 4, jn = (j + 1) % 4;
            grid[NetIndex(a + dirs[j][0], b + dirs[j][1])] = x[r.m[jj]];
            grid[NetIndex(a + dirs[j][0] + dirs[jn][0], b + dirs[j][1] + dirs[jn][1])] = x[Diagonal(t, r.h[jj])];
        }
    }
    return grid;
}

/// Power coefficients of the Bezier cubic with control values b.
std::array<glm::dvec3, 4> CubicPower(const std::array<glm::dvec3, 4>& b) {
    return {b[0], 3.0 * (b[1] - b[0]), 3.0 * (b[0] - 2.0 * b[1] + b[2]), -b[0] + 3.0 * b[1] - 3.0 * b[2] + b[3]};
}

/// Edge k of a net, traversed from corner k to corner k + 1: its 4 boundary points (row 0) and
/// the 4 points next to them inside (row 1).
void EdgeRows(const Net& net, int k, std::array<glm::dvec3, 4>* row0, std::array<glm::dvec3, 4>* row1) {
    const CornerFrame& c = kCorners[k];
    for (int i = 0; i < 4; ++i) {
        (*row0)[i] = net[NetIndex(c.a + i * c.xa, c.b + i * c.xb)];
        (*row1)[i] = net[NetIndex(c.a + i * c.xa + c.ya, c.b + i * c.xb + c.yb)];
    }
}

/// T(t) x C(t) along edge e, t from edgeVerts[e][0] to [1]: power coefficients, degree 5.
std::array<glm::dvec3, 6> EdgeNormalCurve(const Topology& t, const std::vector<Net>& nets, int e) {
    std::array<glm::dvec3, 4> row0, rowA, rowB, unused;
    const int hA = t.edgeHalf[e][0], hB = t.edgeHalf[e][1];
    const int fA = t.faceOf[hA];
    EdgeRows(nets[fA], hA - t.level->start[fA], &row0, &rowA);
    std::array<glm::dvec3, 4> cross;
    for (int i = 0; i < 4; ++i) cross[i] = 3.0 * (rowA[i] - row0[i]);
    if (hB >= 0) {
        const int fB = t.faceOf[hB];
        EdgeRows(nets[fB], hB - t.level->start[fB], &unused, &rowB);
        // B runs the other way: its point i is A's point 3 - i.
        for (int i = 0; i < 4; ++i) cross[i] = 0.5 * (cross[i] - 3.0 * (rowB[3 - i] - unused[3 - i]));
    }
    const std::array<glm::dvec3, 4> p = CubicPower(row0), c = CubicPower(cross);
    const glm::dvec3 tangent[3] = {p[1], 2.0 * p[2], 3.0 * p[3]};
    std::array<glm::dvec3, 6> out{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) out[i + j] += glm::cross(tangent[i], c[j]);
    return out;
}

/// Q with E(t) - (1 - t) E(0) - t E(1) = t (1 - t) Q(t) (the remainder is rounding).
std::array<glm::dvec3, 4> Bubble(const std::array<glm::dvec3, 6>& e) {
    glm::dvec3 e1(0.0);
    for (const glm::dvec3& c : e) e1 += c;
    // R = E - e0 - (e1 - e0) t has no constant term; S = R / t; Q = S / (1 - t).
    std::array<glm::dvec3, 5> s = {e[1] - (e1 - e[0]), e[2], e[3], e[4], e[5]};
    std::array<glm::dvec3, 4> q;
    q[0] = s[0];
    for (int i = 1; i < 4; ++i) q[i] = s[i] + q[i - 1];
    return q;
}

BicubicPatch PatchOf(const Net& points, bool bspline) {
    const CubicBasis basis = *CubicBasis::Named(bspline ? "b-spline" : "bezier");
    return BicubicPatch::FromControlPoints(points, basis, basis, glm::dmat4(1.0));
}

/// The level-0 data of a variable of `storage` with `values`: the vertex class as it is, the
/// others as one value per face corner.
VariableData FirstData(const Level& level, StorageClass storage, const std::vector<glm::dvec3>& values) {
    VariableData data;
    data.perVertex = storage == StorageClass::Vertex;
    if (data.perVertex) {
        data.values = values;
        return data;
    }
    for (int f = 0; f < level.Faces(); ++f)
        for (int h = level.start[f]; h < level.start[f + 1]; ++h) {
            size_t i = 0;
            switch (storage) {
                case StorageClass::Constant: i = 0; break;
                case StorageClass::Uniform: i = static_cast<size_t>(f); break;
                case StorageClass::Varying: i = static_cast<size_t>(level.verts[h]); break;
                default: i = static_cast<size_t>(h); break;
            }
            data.values.push_back(values[i]);
        }
    return data;
}

/// Level 0 of `mesh`: its faces, tags, st (data 0, lifted to (s, t, 0)) and other variables.
Level FirstLevel(const SubdivisionMesh& mesh) {
    Level level;
    level.P = mesh.points;
    level.start.push_back(0);
    for (int n : mesh.faceSizes) level.start.push_back(level.start.back() + n);
    level.verts = mesh.faceVerts;
    level.hole.assign(mesh.faceSizes.size(), 0);
    for (int f : mesh.holes) level.hole[f] = 1;
    level.corner.assign(mesh.points.size(), 0);
    for (const auto& [v, s] : mesh.corners)
        if (s > 0) level.corner[v] = 1;
    for (const SubdivisionMesh::Crease& c : mesh.creases)
        for (size_t i = 0; i + 1 < c.chain.size(); ++i)
            if (c.sharpness > 0) level.sharp[std::minmax(c.chain[i], c.chain[i + 1])] = c.sharpness;
    if (mesh.st) {
        std::vector<glm::dvec3> lifted;
        for (const glm::dvec2& p : mesh.st->values) lifted.emplace_back(p, 0.0);
        level.data.push_back(FirstData(level, mesh.st->storage, lifted));
    }
    for (const SubdivVariable& var : mesh.variables) level.data.push_back(FirstData(level, var.storage, var.values));
    return level;
}

}  // namespace

std::string ToString(const SubdivPatch& p) {
    std::ostringstream out;
    out << (p.regular ? "subdivision (regular) face " : "subdivision (approximated) face ") << p.controlFace << ": "
        << ToString(p.geometry);
    return out.str();
}

SubdivisionMesh RefineSubdivisionMesh(const SubdivisionMesh& mesh, int levels) {
    Level level = FirstLevel(mesh);
    for (int i = 0; i < levels; ++i) {
        Topology t;
        if (!BuildTopology(level, &t).empty()) break;
        level = Refine(t);
    }
    SubdivisionMesh out;
    out.points = level.P;
    for (int f = 0; f < level.Faces(); ++f) {
        out.faceSizes.push_back(level.Size(f));
        if (level.hole[f]) out.holes.push_back(f);
    }
    out.faceVerts = level.verts;
    for (const auto& [edge, s] : level.sharp) out.creases.push_back({{edge.first, edge.second}, s});
    for (size_t v = 0; v < level.corner.size(); ++v)
        if (level.corner[v]) out.corners.emplace_back(static_cast<int>(v), kInfiniteSharpness);
    out.boundary = mesh.boundary;
    return out;
}

std::string BuildSubdivisionPatches(const SubdivisionMesh& mesh, SubdivisionResult* out, int levels) {
    Level level = FirstLevel(mesh);
    // Valence-2 boundary vertices are corners when the tag asks for them.
    Topology t;
    if (std::string problem = BuildTopology(level, &t); !problem.empty()) return problem;
    if (mesh.boundary == SubdivBoundary::EdgesAndCorners)
        for (size_t v = 0; v < level.P.size(); ++v)
            if (t.boundaryVertex[v] && RingOf(t, static_cast<int>(v)).FaceCount() == 1) level.corner[v] = 1;
    // Without interpolateboundary, control faces with a boundary vertex only shape their
    // neighbours: they are refined as holes are.
    if (mesh.boundary == SubdivBoundary::None)
        for (int f = 0; f < level.Faces(); ++f)
            for (int h = level.start[f]; h < level.start[f + 1]; ++h)
                if (t.boundaryVertex[level.verts[h]]) level.hole[f] = 1;
    if (levels < 0) {
        // None if every face is a regular quad, else the default, more for semi-sharp creases.
        const std::vector<VertexInfo> info = ClassifyVertices(t);
        bool allRegular = true;
        for (int f = 0; f < level.Faces() && allRegular; ++f) {
            if (level.Size(f) != 4) allRegular = false;
            for (int h = level.start[f]; h < level.start[f + 1] && allRegular; ++h)
                allRegular = info[level.verts[h]].regular;
        }
        levels = allRegular ? 0 : kSubdivisionLevels;
        // A dense control mesh takes fewer steps (each makes four faces of one), so that its
        // patches stay within kSubdivisionPatchBudget; faces that are not quads need one.
        bool allQuads = true;
        for (int f = 0; f < level.Faces(); ++f) allQuads = allQuads && level.Size(f) == 4;
        const int fewest = allQuads ? 0 : 1;
        while (levels > fewest && (size_t(level.Faces()) << (2 * levels)) > kSubdivisionPatchBudget) --levels;
        for (const auto& [edge, s] : level.sharp)
            if (s < kInfiniteSharpness / 2)
                levels = std::max(levels, std::min(kMaxSubdivisionLevels, static_cast<int>(std::ceil(s))));
    }
    for (int i = 0; i < levels; ++i) {
        level = Refine(t);
        t = Topology();
        if (std::string problem = BuildTopology(level, &t); !problem.empty()) return problem;
    }
    t.level = &level;
    out->levels = levels;
    const std::vector<VertexInfo> info = ClassifyVertices(t);
    const LimitData limits = ComputeLimits(t, info, level.P);
    out->refinedPoints = limits.limit;
    std::vector<LimitData> dataLimits(level.data.size());
    for (size_t k = 0; k < level.data.size(); ++k)
        if (level.data[k].perVertex) dataLimits[k] = ComputeLimits(t, info, level.data[k].values);
    out->variables.assign(mesh.variables.size(), {});

    // Bezier nets of every face (neighbours' nets enter the edge normal curves), then the
    // shared edge curves and vertex normals.
    const int nF = level.Faces();
    std::vector<Net> nets(nF);
    for (int f = 0; f < nF; ++f)
        if (level.Size(f) == 4) nets[f] = BezierNet(t, info, limits, level.P, f);
    const size_t nE = t.edgeVerts.size();
    std::vector<std::array<glm::dvec3, 6>> curves(nE);
    std::vector<glm::dvec3> vertexNormal(level.P.size(), glm::dvec3(0.0));
    std::vector<int> normalCount(level.P.size(), 0);
    for (size_t e = 0; e < nE; ++e) {
        curves[e] = EdgeNormalCurve(t, nets, static_cast<int>(e));
        glm::dvec3 atEnd(0.0);
        for (const glm::dvec3& c : curves[e]) atEnd += c;
        vertexNormal[t.edgeVerts[e][0]] += curves[e][0];
        vertexNormal[t.edgeVerts[e][1]] += atEnd;
        ++normalCount[t.edgeVerts[e][0]];
        ++normalCount[t.edgeVerts[e][1]];
    }
    for (size_t v = 0; v < vertexNormal.size(); ++v)
        if (normalCount[v]) vertexNormal[v] /= double(normalCount[v]);
    std::vector<std::array<glm::dvec3, 4>> bubbles(nE);
    for (size_t e = 0; e < nE; ++e) bubbles[e] = Bubble(curves[e]);

    out->patches.clear();
    out->regularPatches = 0;
    for (int f = 0; f < nF; ++f) {
        if (level.hole[f]) continue;
        bool regular = true;
        for (int h = level.start[f]; h < level.start[f + 1]; ++h) regular &= info[level.verts[h]].regular;
        SubdivPatch patch;
        patch.controlFace = f;  // replaced by the caller's numbering below
        patch.regular = regular;
        patch.geometry = regular ? PatchOf(BSplineGrid(t, info, level.P, f), true) : PatchOf(nets[f], false);
        if (!regular) {
            const int h0 = level.start[f];
            const int cornerSlot[4] = {0, 1, 3, 2};  // corner k -> RenderMan's patch order
            for (int k = 0; k < 4; ++k) {
                const int h = h0 + k, e = t.edgeOf[h];
                patch.cornerNormal[cornerSlot[k]] = vertexNormal[t.Src(h)];
                const bool sameWay = t.edgeVerts[e][0] == t.Src(h);
                patch.edgeQ[k] = bubbles[e];
                patch.edgeReversed[k] = (k >= 2) == sameWay;
            }
        }
        // Each variable over the patch: vertex values by the surface's own rules, the others
        // bilinear over the face (the Bezier net of the bilinear patch of its corners).
        for (size_t k = 0; k < level.data.size(); ++k) {
            const VariableData& data = level.data[k];
            BicubicPatch field;
            if (data.perVertex) {
                field = regular ? PatchOf(BSplineGrid(t, info, data.values, f), true)
                                : PatchOf(BezierNet(t, info, dataLimits[k], data.values, f), false);
            } else {
                const int h0 = level.start[f];
                const glm::dvec3 c00 = data.values[h0], c10 = data.values[h0 + 1], c11 = data.values[h0 + 2],
                                 c01 = data.values[h0 + 3];
                Net net;
                for (int a = 0; a < 4; ++a)
                    for (int b = 0; b < 4; ++b) {
                        const double u = a / 3.0, v = b / 3.0;
                        net[NetIndex(a, b)] =
                            (1 - u) * (1 - v) * c00 + u * (1 - v) * c10 + (1 - u) * v * c01 + u * v * c11;
                    }
                field = PatchOf(net, false);
            }
            if (mesh.st && k == 0) {
                patch.hasST = true;
                patch.st = field;
            } else {
                out->variables[k - (mesh.st ? 1 : 0)].push_back(field);
            }
        }
        out->regularPatches += regular;
        out->patches.push_back(patch);
    }
    // Each refined face comes from control face (index / 4^levels) after the first step splits
    // control face f into faceSizes[f] quads.
    if (levels > 0) {
        std::vector<int> firstChild;
        int count = 0;
        for (int n : mesh.faceSizes) {
            firstChild.push_back(count);
            count += n;
        }
        const int perChild = 1 << (2 * (levels - 1));
        for (SubdivPatch& p : out->patches) {
            const int child = p.controlFace / perChild;
            p.controlFace =
                static_cast<int>(std::upper_bound(firstChild.begin(), firstChild.end(), child) - firstChild.begin()) -
                1;
        }
    }
    return "";
}

bool SubdivPatches::PatchColor(size_t index, int k, ColorField* out) const {
    if (!colorFields[k].empty()) {
        const std::array<glm::dvec3, 16>& c = colorFields[k][index];
        out->degreeU = out->degreeV = 3;
        out->c.assign(c.begin(), c.end());
        out->w.clear();
        return true;
    }
    const std::optional<ColorValues>& color = colors[k];
    if (!color) return false;
    const bool uniform = color->storage == StorageClass::Uniform;
    *out = ColorField();
    out->c = {color->values[uniform ? size_t(patches[index].controlFace) : 0]};
    return true;
}

}  // namespace affray::renderer
