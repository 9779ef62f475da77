// scene/motion.h: a transform that moves while the shutter is open (RI 3.2 section 4.6, MotionBegin
// around transform requests): its matrix at each of a few increasing times, linear in between.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace affray::renderer {

/// The matrix of a moving transform at each of its times (column vectors, as every matrix of the
/// scene). Between two times each entry is interpolated linearly, so a point carried by it moves
/// on a straight line between its places at the two times (and the box of the places at the
/// times holds it throughout). Before the first time it stands at the first; after the last at
/// the last. RenderMan leaves the interpolation to the renderer; this is the simplest one that
/// keeps bounds exact, and the one most renderers use for few, close samples.
struct MotionPath {
    std::vector<double> times;         ///< At least two, increasing.
    std::vector<glm::dmat4> matrices;  ///< One per time.

    /// The matrix at `time`.
    glm::dmat4 At(double time) const;

    /// The path through `matrices` at `times`, or null if every matrix is the first (the
    /// transform does not move). Both have the same size, at least 1; the times increase.
    static std::shared_ptr<const MotionPath> Make(const std::vector<double>& times,
                                                  const std::vector<glm::dmat4>& matrices);
};

/// The matrix at `time` of `path`, or `still` when there is no path.
inline glm::dmat4 MatrixAt(const MotionPath* path, const glm::dmat4& still, double time) {
    return path ? path->At(time) : still;
}

}  // namespace affray::renderer
