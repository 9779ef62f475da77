// scene/geometry/primvar.h: what every base surface shares about primitive variables: their
// storage classes, and the colour fields (Cs, Os) that shading reads at a hit. A primitive's
// field is built once by the RIB reader from its values (bilinear between four corner values,
// or in the surface's own basis), so shading evaluates one polynomial whatever the surface.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace affray::renderer {

/// How a primitive variable's values map onto a primitive (RI Spec 3.2 section 4.1, table 4.1):
/// one value; one per face (patch, segment); one per point for Varying (interpolated bilinearly)
/// and Vertex (interpolated as P is); one per face corner. Polygon meshes, subdivision meshes
/// and NuPatches all read their "st" through it (a NuPatch has no FaceVarying: its reader says so).
enum class StorageClass { Constant, Uniform, Varying, Vertex, FaceVarying };

/// A colour primitive variable (Cs or Os) of a primitive as given: one value, or one per face
/// (patch), per point or per face corner, as its storage class says.
struct ColorValues {
    StorageClass storage = StorageClass::Constant;
    std::vector<glm::dvec3> values;
};

/// A colour primitive variable (Cs or Os) over one primitive's own parameters (s, t) in [0,1]^2
/// (the intersector's, before a patch mesh's range maps them): the polynomial
///     C(s, t) = sum over i <= degreeU, j <= degreeV of c[(degreeV + 1) i + j] s^i t^j,
/// divided by the polynomial W of the same form with coefficients `w` when `w` is not empty
/// (vertex values on a rational surface, weighted as its points are). A bilinear field is
/// degree 1 x 1, a bicubic one 3 x 3, a NuPatch span's its degrees.
struct ColorField {
    int degreeU = 0, degreeV = 0;
    std::vector<glm::dvec3> c{glm::dvec3(0.0)};
    std::vector<double> w;

    /// The bilinear field of four corner values in RenderMan's patch order (u0v0, u1v0, u0v1,
    /// u1v1): varying values, and a mesh piece's values at its corners.
    static ColorField Bilinear(const std::array<glm::dvec3, 4>& corners);
    /// The value at (s, t).
    glm::dvec3 At(double s, double t) const;
    /// Whether the field is one colour everywhere (*value, then): every coefficient but the
    /// first zero, and no weights.
    bool ConstantP(glm::dvec3* value) const;
    /// Whether every coefficient is finite.
    bool FiniteP() const;
};

/// "1x1 corners [r g b] [r g b] [r g b] [r g b]": the degrees and the values at the corners.
std::string ToString(const ColorField& f);

}  // namespace affray::renderer
