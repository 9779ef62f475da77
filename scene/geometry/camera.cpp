// scene/geometry/camera.cpp: RenderMan-style primary rays (conventions in camera.h).
#include "scene/geometry/camera.h"

#include <algorithm>
#include <cmath>

namespace affray::renderer {

Camera::Camera(const CameraDesc& desc) : m_desc(desc) {
    m_cameraToWorld = glm::inverse(desc.worldToCamera);

    // Default screen window: the shorter axis of the frame spans [-1, 1].
    double aspect = desc.frameAspectRatio.value_or(desc.xres * desc.pixelAspect / desc.yres);
    if (desc.screenWindow) {
        const glm::dvec4& w = *desc.screenWindow;
        m_left = w.x, m_right = w.y, m_bottom = w.z, m_top = w.w;
    } else if (aspect >= 1) {
        m_left = -aspect, m_right = aspect, m_bottom = -1, m_top = 1;
    } else {
        m_left = -1, m_right = 1, m_bottom = -1 / aspect, m_top = 1 / aspect;
    }
    m_tanHalfFov = std::tan(glm::radians(desc.fovDegrees) / 2);
    if (LensP(desc)) m_lensRadius = 0.5 * desc.focalLength / desc.fstop;

    // Pixel size at the image center, measured between world-space rays through the pixel's
    // opposite edges, so any scale in worldToCamera is accounted for.
    double cx = desc.xres / 2.0, cy = desc.yres / 2.0;
    Ray left = GenerateRay(cx - 0.5, cy), right = GenerateRay(cx + 0.5, cy);
    Ray top = GenerateRay(cx, cy - 0.5), bottom = GenerateRay(cx, cy + 0.5);
    if (desc.perspective) {
        auto angle = [](const glm::dvec3& a, const glm::dvec3& b) {
            // atan2 of |a x b| and a . b is accurate for the tiny angles of a pixel.
            return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
        };
        m_pixelAngle = std::max(angle(left.dir, right.dir), angle(top.dir, bottom.dir));
    } else {
        m_pixelWidth = std::max(glm::length(right.origin - left.origin), glm::length(bottom.origin - top.origin));
    }
}

void Camera::CameraSpaceRay(double rasterX, double rasterY, glm::dvec3* origin, glm::dvec3* dir) const {
    // Raster y grows downward; screen y grows upward.
    double sx = m_left + (m_right - m_left) * (rasterX / m_desc.xres);
    double sy = m_top - (m_top - m_bottom) * (rasterY / m_desc.yres);
    if (m_desc.perspective) {
        *origin = glm::dvec3(0.0);
        *dir = glm::dvec3(sx * m_tanHalfFov, sy * m_tanHalfFov, 1.0);
    } else {
        *origin = glm::dvec3(sx, sy, 0.0);
        *dir = glm::dvec3(0.0, 0.0, 1.0);
    }
}

bool Camera::ToRaster(const glm::dvec3& p, glm::dvec2* raster) const {
    double sx = p.x, sy = p.y;
    if (m_desc.perspective) {
        if (!(p.z > 0)) return false;
        sx = p.x / (p.z * m_tanHalfFov);
        sy = p.y / (p.z * m_tanHalfFov);
    }
    *raster =
        glm::dvec2((sx - m_left) / (m_right - m_left) * m_desc.xres, (m_top - sy) / (m_top - m_bottom) * m_desc.yres);
    return true;
}

Ray Camera::GenerateRay(double rasterX, double rasterY) const {
    glm::dvec3 origin, dir;
    CameraSpaceRay(rasterX, rasterY, &origin, &dir);
    Ray ray;
    ray.origin = glm::dvec3(m_cameraToWorld * glm::dvec4(origin, 1.0));
    ray.dir = glm::normalize(glm::dvec3(m_cameraToWorld * glm::dvec4(dir, 0.0)));
    return ray;
}

Ray Camera::GenerateRay(double rasterX, double rasterY, const glm::dvec2& lens) const {
    if (m_lensRadius <= 0) return GenerateRay(rasterX, rasterY);
    return LensRay(rasterX, rasterY, lens, m_cameraToWorld);
}

Ray Camera::GenerateRay(double rasterX, double rasterY, const glm::dvec2& lens, double time) const {
    Ray ray = m_desc.motion ? LensRay(rasterX, rasterY, lens, glm::inverse(m_desc.motion->At(time)))
                            : GenerateRay(rasterX, rasterY, lens);
    ray.time = time;
    return ray;
}

Ray Camera::LensRay(double rasterX, double rasterY, const glm::dvec2& lens, const glm::dmat4& cameraToWorld) const {
    glm::dvec3 origin, dir;
    CameraSpaceRay(rasterX, rasterY, &origin, &dir);
    if (m_lensRadius > 0) {
        // dir has z = 1: the pinhole ray meets the focal plane at dir * focalDistance.
        const glm::dvec3 focus = dir * m_desc.focalDistance;
        const glm::dvec2 d = m_lensRadius * LensPoint(lens);
        origin = glm::dvec3(d.x, d.y, 0.0);
        dir = focus - origin;
    }
    Ray ray;
    ray.origin = glm::dvec3(cameraToWorld * glm::dvec4(origin, 1.0));
    ray.dir = glm::normalize(glm::dvec3(cameraToWorld * glm::dvec4(dir, 0.0)));
    return ray;
}

glm::dvec2 Camera::LensPoint(const glm::dvec2& u) {
    const double a = 2 * u.x - 1, b = 2 * u.y - 1;
    if (a == 0 && b == 0) return {0, 0};
    constexpr double kQuarterPi = 0.78539816339744830962;
    double r, phi;
    if (std::fabs(a) > std::fabs(b)) {
        r = a;
        phi = kQuarterPi * (b / a);
    } else {
        r = b;
        phi = 2 * kQuarterPi - kQuarterPi * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

glm::dvec3 Camera::Position() const { return glm::dvec3(m_cameraToWorld[3]); }

}  // namespace affray::renderer
