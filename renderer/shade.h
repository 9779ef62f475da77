// renderer/shade.h: RenderMan's built-in surface models and light sources, at one hit point.
#pragma once

#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/scene.h"

namespace affray::renderer {

/// A point to shade, in world space.
struct ShadingPoint {
    glm::dvec3 P;   // the displaced surface point
    glm::dvec3 Nf;  // unit shading normal, facing the viewer
    glm::dvec3 V;   // unit vector from P towards the viewer
};

/// Returns true if the segment from the shading point towards a light is blocked; `toLight` is a
/// unit vector and `distance` the distance to the light (infinite for distant lights).
using OcclusionTest = std::function<bool(const glm::dvec3& toLight, double distance)>;

/// The colour of `sp` under `lights` for the surface model `surface` with colour Cs, following the
/// RenderMan shaders "matte" and "plastic" (Ka*ambient + Kd*diffuse, plus Ks*specular for plastic).
glm::dvec3 ShadeSurface(const SurfaceDesc& surface, const glm::dvec3& Cs, const ShadingPoint& sp,
                        const std::vector<LightDesc>& lights, const OcclusionTest& occluded);

}  // namespace affray::renderer
