// renderer/geometry/bicubic.cpp: the predefined cubic bases and the conversion of a bicubic patch's
// control points to the power basis (renderer/geometry/bicubic.h).
#include "renderer/geometry/bicubic.h"

#include "renderer/geometry/pole.h"

#include <cmath>
#include <sstream>

namespace affray::renderer {

namespace {

struct NamedBasis {
    const char* name;
    int step;
    double scale;
    std::array<double, 16> m;  // times scale
};

// RI 3.2 section 5.2 (RiBezierBasis ... RiPowerBasis), with the steps its table gives. The hermite
// matrix takes the geometry (point0, vector0, point1, vector1), so that step 2 walks a mesh.
const NamedBasis kBases[] = {
    {"bezier", 3, 1.0, {-1, 3, -3, 1, 3, -6, 3, 0, -3, 3, 0, 0, 1, 0, 0, 0}},
    {"b-spline", 1, 1.0 / 6.0, {-1, 3, -3, 1, 3, -6, 3, 0, -3, 0, 3, 0, 1, 4, 1, 0}},
    {"catmull-rom", 1, 0.5, {-1, 3, -3, 1, 2, -5, 4, -1, -1, 0, 1, 0, 0, 2, 0, 0}},
    {"hermite", 2, 1.0, {2, 1, -2, 1, -3, -2, 3, -1, 0, 1, 0, 0, 1, 0, 0, 0}},
    {"power", 4, 1.0, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
};

}  // namespace

std::optional<CubicBasis> CubicBasis::Named(const std::string& name) {
    for (const NamedBasis& b : kBases) {
        if (name != b.name) continue;
        CubicBasis out;
        for (int i = 0; i < 16; ++i) out.m[i] = b.m[i] * b.scale;
        out.step = b.step;
        out.name = b.name;
        return out;
    }
    return std::nullopt;
}

const char* CubicBasis::NameList() { return "\"bezier\", \"b-spline\", \"catmull-rom\", \"hermite\" or \"power\""; }

std::string ToString(const CubicBasis& b) {
    std::ostringstream out;
    if (!b.name.empty()) {
        out << b.name;
    } else {
        out << '[';
        for (int i = 0; i < 16; ++i) out << (i ? " " : "") << b.m[i];
        out << ']';
    }
    out << ' ' << b.step;
    return out.str();
}

BicubicPatch BicubicPatch::FromControlPoints(const std::array<glm::dvec3, 16>& points, const CubicBasis& uBasis,
                                             const CubicBasis& vBasis, const glm::dmat4& objectToWorld) {
    // C = Mu G Mv^T, with G[a][b] the control point of u index a and v index b (points[4 b + a]);
    // C[a][b] is then the coefficient of u^(3-a) v^(3-b). The same product of absolute values
    // bounds the size of the terms each coefficient sums, for the noise floor below.
    std::array<glm::dvec3, 16> mg{}, mgAbs{};  // Mu G, |Mu| |G|
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            glm::dvec3 sum(0.0), sumAbs(0.0);
            for (int k = 0; k < 4; ++k) {
                sum += uBasis.m[4 * a + k] * points[4 * b + k];
                sumAbs += std::fabs(uBasis.m[4 * a + k]) * glm::abs(points[4 * b + k]);
            }
            mg[4 * a + b] = sum;
            mgAbs[4 * a + b] = sumAbs;
        }
    const glm::dmat3 linear(objectToWorld);
    glm::dmat3 linearAbs;
    for (int col = 0; col < 3; ++col) linearAbs[col] = glm::abs(linear[col]);
    const glm::dvec3 translation(objectToWorld[3]);
    BicubicPatch patch;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            glm::dvec3 sum(0.0), sumAbs(0.0);
            for (int k = 0; k < 4; ++k) {
                sum += mg[4 * a + k] * vBasis.m[4 * b + k];
                sumAbs += mgAbs[4 * a + k] * std::fabs(vBasis.m[4 * b + k]);
            }
            glm::dvec3 c = linear * sum;
            const glm::dvec3 size = linearAbs * sumAbs;
            // A coefficient that cancels in exact arithmetic (a bezier patch whose control points
            // lie on a bilinear surface has no u^2, u^3, v^2, v^3 terms) is left with rounding
            // noise of a few ulps of the terms summed: zero it, so that the evaluation skips it.
            // The surface moves by less than 1e-14 of the terms' size, far below any tolerance.
            for (int i = 0; i < 3; ++i)
                if (std::fabs(c[i]) <= 1e-14 * size[i]) c[i] = 0;
            if (a == 3 && b == 3) c += translation;  // the u^0 v^0 term: the only point among them
            patch.c[4 * (3 - a) + (3 - b)] = c;
        }
    patch.poles = FindPatchPoles(patch);
    return patch;
}

glm::dvec3 BicubicPatch::At(double u, double v) const {
    const SurfaceFrame<double> f = BicubicFrame<double>(*this, u, v);
    return {f.P.x, f.P.y, f.P.z};
}

bool BicubicPatch::FiniteP() const {
    for (const glm::dvec3& x : c)
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(x[i])) return false;
    return true;
}

std::string ToString(const BicubicPatch& p) {
    std::ostringstream out;
    out << "bicubic [";
    for (int k = 0; k < 16; ++k) out << (k ? " " : "") << '[' << p.c[k].x << ' ' << p.c[k].y << ' ' << p.c[k].z << ']';
    out << ']';
    return out.str();
}

}  // namespace affray::renderer
