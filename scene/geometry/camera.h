// scene/geometry/camera.h: camera rays from raster positions, following RenderMan's camera model.
// Owns the raster -> screen -> camera -> world mapping (RI Spec 3.2): the frame aspect a is
// FrameAspectRatio if given, else xres * pixelAspect / yres; the screen window is ScreenWindow if
// given, else [-a,a] x [-1,1] when a >= 1 and [-1,1] x [-1/a,1/a] otherwise. The screen window
// always maps onto the whole raster (as PRMan does): a frame aspect that differs from the image's
// stretches the picture rather than letterboxing it. CropWindow and Clipping are the renderer's.
// Perspective: screen coordinate 1 lies at tan(fov/2) on the plane z = 1 of camera space (so with
// the default window fov spans the shorter image axis). Orthographic: screen coordinates are
// camera x, y and every ray runs along +z. Camera space is left-handed: +x right,
// +y up, +z into the scene. Raster (0,0) is the top-left corner of the image.
// Depth of field (DepthOfField fstop focallength focaldistance, perspective only): a thin lens of
// radius focallength / (2 fstop) in the plane z = 0 of camera space, focused on the plane
// z = focaldistance: the ray of a raster position and a point of the lens starts at that point
// and passes through where the pinhole ray of the raster position meets the focal plane, so the
// focal plane is sharp and a point at depth z blurs over a circle of diameter
// 2 radius |z - focaldistance| / z (on the plane z = 1, in camera units).
#pragma once

#include <glm/glm.hpp>
#include <sstream>
#include <string>

#include "scene/scene.h"

namespace affray::renderer {

/// A ray in world space: points origin + t * dir for t >= 0.
struct Ray {
    glm::dvec3 origin{0.0};
    glm::dvec3 dir{0.0, 0.0, 1.0};  ///< Unit length.
    /// When the ray looks at the scene (Shutter): where moving primitives and the camera are.
    double time = 0;
};

inline std::string ToString(const Ray& r) { return "ray origin=" + ToString(r.origin) + " dir=" + ToString(r.dir); }

/// Generates primary rays for a CameraDesc. Immutable after construction; safe to share between
/// threads.
class Camera {
  public:
    /// `desc.worldToCamera` must be invertible, xres, yres, pixelAspect and frameAspectRatio
    /// positive and the screen window not empty (the RIB reader guarantees all of these).
    explicit Camera(const CameraDesc& desc);

    /// The world-space ray through raster position (rasterX, rasterY): (0,0) is the top-left
    /// corner of the image, (xres, yres) the bottom-right, pixel centers at +0.5.
    Ray GenerateRay(double rasterX, double rasterY) const;
    /// The same through the point of the lens `lens` (in [0, 1]^2, mapped onto the lens's disc
    /// preserving area and strata: LensPoint); the pinhole ray if the camera has no lens.
    Ray GenerateRay(double rasterX, double rasterY, const glm::dvec2& lens) const;
    /// The same at `time`, from where a moving camera (CameraDesc::motion) is then; the ray
    /// carries the time for the primitives that move.
    Ray GenerateRay(double rasterX, double rasterY, const glm::dvec2& lens, double time) const;

    /// Whether rays start across a lens (DepthOfField with a finite fstop, perspective).
    bool HasLens() const { return m_lensRadius > 0; }
    /// The lens's radius in camera space (0: a pinhole).
    double LensRadius() const { return m_lensRadius; }
    /// The point of the unit disc for `u` in [0, 1]^2 (Shirley and Chiu's concentric map: equal
    /// areas to equal areas, and squares of a grid to compact pieces of the disc).
    static glm::dvec2 LensPoint(const glm::dvec2& u);

    /// The camera's eye point in world space (for orthographic cameras, the camera-space origin).
    glm::dvec3 Position() const;

    /// The angle one pixel subtends at the image center, in radians: the larger of its width and
    /// height. A perspective ray's footprint at distance d is about d * PixelAngle(). Zero for
    /// orthographic cameras, whose footprint is PixelWidth().
    double PixelAngle() const { return m_pixelAngle; }

    /// The world-space width of one pixel for orthographic cameras (larger of width and height);
    /// zero for perspective cameras.
    double PixelWidth() const { return m_pixelWidth; }

    /// The world-space width of one pixel at distance `distance` along a camera ray:
    /// PixelWidth() + distance * PixelAngle().
    double Footprint(double distance) const { return m_pixelWidth + distance * m_pixelAngle; }

    const CameraDesc& Desc() const { return m_desc; }

    /// The screen window (left, right, bottom, top) in screen coordinates.
    glm::dvec4 ScreenWindow() const { return {m_left, m_right, m_bottom, m_top}; }

    /// The raster position of a camera-space point (the inverse of CameraSpaceRay); false for a
    /// perspective camera and a point not in front of the eye (z <= 0), which has none.
    bool ToRaster(const glm::dvec3& cameraPoint, glm::dvec2* raster) const;

  private:
    /// The camera-space ray through a raster position, before the world transform.
    void CameraSpaceRay(double rasterX, double rasterY, glm::dvec3* origin, glm::dvec3* dir) const;
    /// The ray through the lens point (pinhole: the centre) carried to world by `cameraToWorld`.
    Ray LensRay(double rasterX, double rasterY, const glm::dvec2& lens, const glm::dmat4& cameraToWorld) const;

    CameraDesc m_desc;
    glm::dmat4 m_cameraToWorld{1.0};
    double m_left = -1, m_right = 1, m_bottom = -1, m_top = 1;
    double m_tanHalfFov = 1;
    double m_pixelAngle = 0, m_pixelWidth = 0;
    double m_lensRadius = 0;
};

}  // namespace affray::renderer
