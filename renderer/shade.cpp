// renderer/shade.cpp: ambient, diffuse and specular sums over the lights, with shadows.
#include "renderer/shade.h"

#include <cmath>

namespace affray::renderer {

glm::dvec3 ShadeSurface(const SurfaceDesc& surface, const glm::dvec3& Cs, const ShadingPoint& sp,
                        const std::vector<LightDesc>& lights, const OcclusionTest& occluded) {
    glm::dvec3 ambient(0.0), diffuse(0.0), specular(0.0);
    for (const LightDesc& light : lights) {
        glm::dvec3 Cl = light.intensity * light.color;
        if (light.kind == LightDesc::Kind::Ambient) {
            ambient += Cl;
            continue;
        }
        glm::dvec3 L;
        double distance;
        if (light.kind == LightDesc::Kind::Distant) {
            L = glm::normalize(light.from - light.to);
            distance = INFINITY;
        } else {
            glm::dvec3 toLight = light.from - sp.P;
            distance = glm::length(toLight);
            if (!(distance > 0)) continue;
            L = toLight / distance;
            Cl /= distance * distance;  // pointlight: intensity falls off with the squared distance
        }
        double cosine = glm::dot(sp.Nf, L);
        if (cosine <= 0) continue;  // the light is behind the surface: no need for a shadow ray
        if (occluded(L, distance)) continue;
        diffuse += Cl * cosine;
        if (surface.model == SurfaceDesc::Model::Plastic && surface.roughness > 0) {
            glm::dvec3 H = glm::normalize(L + sp.V);
            specular += Cl * std::pow(std::max(0.0, glm::dot(sp.Nf, H)), 1.0 / surface.roughness);
        }
    }
    glm::dvec3 color = Cs * (surface.Ka * ambient + surface.Kd * diffuse);
    if (surface.model == SurfaceDesc::Model::Plastic) color += surface.specularColor * surface.Ks * specular;
    return color;
}

}  // namespace affray::renderer
