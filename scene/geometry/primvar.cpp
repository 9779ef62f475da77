// scene/geometry/primvar.cpp: colour fields (scene/geometry/primvar.h).
#include "scene/geometry/primvar.h"

#include <cmath>
#include <sstream>

namespace affray::renderer {

ColorField ColorField::Bilinear(const std::array<glm::dvec3, 4>& corners) {
    // f0 + (f1 - f0) s + (f2 - f0) t + (f0 - f1 - f2 + f3) s t
    ColorField f;
    f.degreeU = f.degreeV = 1;
    f.c = {corners[0], corners[2] - corners[0], corners[1] - corners[0],
           corners[0] - corners[1] - corners[2] + corners[3]};
    return f;
}

glm::dvec3 ColorField::At(double s, double t) const {
    // Horner in t for each power of s, then in s; W likewise.
    glm::dvec3 value(0.0);
    double weight = 0;
    for (int i = degreeU; i >= 0; --i) {
        glm::dvec3 row(0.0);
        double rowW = 0;
        for (int j = degreeV; j >= 0; --j) {
            const size_t k = static_cast<size_t>(degreeV + 1) * static_cast<size_t>(i) + static_cast<size_t>(j);
            row = row * t + c[k];
            if (!w.empty()) rowW = rowW * t + w[k];
        }
        value = value * s + row;
        weight = weight * s + rowW;
    }
    return w.empty() ? value : value / weight;
}

bool ColorField::ConstantP(glm::dvec3* value) const {
    if (!w.empty()) return false;
    for (size_t k = 1; k < c.size(); ++k)
        if (c[k] != glm::dvec3(0.0)) return false;
    *value = c[0];
    return true;
}

bool ColorField::FiniteP() const {
    for (const glm::dvec3& x : c)
        if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) return false;
    for (double x : w)
        if (!std::isfinite(x)) return false;
    return true;
}

std::string ToString(const ColorField& f) {
    std::ostringstream out;
    out << f.degreeU << 'x' << f.degreeV << (f.w.empty() ? "" : " rational") << " corners";
    for (int k = 0; k < 4; ++k) {
        const glm::dvec3 v = f.At(k & 1, k >> 1);
        out << " [" << v.x << ' ' << v.y << ' ' << v.z << ']';
    }
    return out.str();
}

}  // namespace affray::renderer
