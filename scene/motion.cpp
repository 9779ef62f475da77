// scene/motion.cpp: moving transforms (motion.h).
#include "scene/motion.h"

#include <algorithm>

namespace affray::renderer {

glm::dmat4 MotionPath::At(double time) const {
    if (!(time > times.front())) return matrices.front();  // NaN too
    if (time >= times.back()) return matrices.back();
    // The segment [times[i], times[i + 1]) that holds `time`.
    const size_t i = size_t(std::upper_bound(times.begin(), times.end(), time) - times.begin()) - 1;
    const double w = (time - times[i]) / (times[i + 1] - times[i]);
    return matrices[i] * (1.0 - w) + matrices[i + 1] * w;
}

std::shared_ptr<const MotionPath> MotionPath::Make(const std::vector<double>& times,
                                                   const std::vector<glm::dmat4>& matrices) {
    if (times.size() < 2 || times.size() != matrices.size()) return nullptr;
    if (std::all_of(matrices.begin(), matrices.end(), [&](const glm::dmat4& m) { return m == matrices.front(); }))
        return nullptr;
    return std::make_shared<const MotionPath>(MotionPath{times, matrices});
}

}  // namespace affray::renderer
