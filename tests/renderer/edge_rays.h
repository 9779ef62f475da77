// tests/renderer/edge_rays.h: the crack probe shared by the mesh and subdivision suites. Rays
// from outside aimed at points on the edges of a surface displaced outward: a closed displaced
// surface lies between the ray's origin and the point, so each ray must hit it no farther.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "renderer/intersect.h"
#include "scene/geometry/camera.h"

namespace affray::test {

class EdgeRays {
  public:
    explicit EdgeRays(std::vector<std::unique_ptr<renderer::SurfaceIntersector>> intersectors)
        : m_intersectors(std::move(intersectors)) {}

    /// Four rays at `target` from 4 units out: along `normal`, tilted either way across the edge
    /// (`along` its direction) and along it, each against every intersector. A miss is counted,
    /// and the first three are reported with describe() naming the place.
    template <class Describe>
    void At(const glm::dvec3& target, const glm::dvec3& normal, const glm::dvec3& along, Describe&& describe) {
        const glm::dvec3 side = glm::normalize(glm::cross(normal, along));
        for (const glm::dvec3& tilt : {glm::dvec3(0.0), 0.4 * side, -0.4 * side, 0.3 * along}) {
            const glm::dvec3 dir = glm::normalize(normal + tilt);
            const renderer::Ray ray{target + 4.0 * dir, -dir};
            double best = INFINITY, error = 0;
            for (auto& intersector : m_intersectors) {
                renderer::Hit hit;
                if (intersector->Intersect(ray, 0, best, {1e-5, 0}, false, &hit, m_stats))
                    best = hit.t, error = hit.error;
            }
            ++rays;
            if (!(best <= 4.0 + error + 1e-9) && misses++ < 3)
                UNSCOPED_INFO("miss: " << ToString(ray) << " at " << describe() << " t=" << best);
        }
    }

    int rays = 0, misses = 0;

  private:
    std::vector<std::unique_ptr<renderer::SurfaceIntersector>> m_intersectors;
    renderer::IntersectStats m_stats;
};

}  // namespace affray::test
