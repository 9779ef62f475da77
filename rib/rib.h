// rib/rib.h: reading a RIB file into a SceneDesc.
// The reader follows the RenderMan Interface Specification 3.2 for the requests it implements:
// options (Format, Projection, FrameAspectRatio, ScreenWindow, CropWindow, Clipping, PixelSamples,
// PixelFilter box/gaussian, Exposure, Display with its mode checked, Hider "hidden" "jitter",
// Option "searchpath" "shader" and "archive"), Declare and inline declarations on every parameter
// list, transforms and Begin/End scopes, CoordinateSystem, CoordSysTransform, attributes (Color,
// Opacity 1 1 1, Surface constant/matte/metal/plastic, Displacement, Sides, ReverseOrientation,
// Orientation, Illuminate on),
// lights (ambientlight, distantlight, pointlight, spotlight), ReadArchive, retained objects
// (ObjectBegin, ObjectEnd, ObjectInstance) and geometry (bilinear Patch, Sphere, Cylinder, Cone,
// Disk, Torus, Hyperboloid, Paraboloid). Other RI 3.2 requests, other Option and Attribute names,
// other hiders and unknown shaders are skipped with one warning per name, unless ignoring them
// would change the geometry (other primitives, Skew, Perspective, MotionBegin, ...), which is an
// error. Problems are reported through diag/diagnostic.h, at the file (the scene or an archive),
// line and column of the token.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "diag/diagnostic.h"
#include "renderer/scene.h"

namespace affray::rib {

using renderer::SceneDesc;

/// Parses RIB text. On success returns the scene (with path = pathForMessages), with any warnings
/// in *report (may be null). On failure returns nullopt with the first error in *report; parsing
/// stops there. Never throws on bad input.
std::optional<SceneDesc> ParseRib(std::string_view text, const std::string& pathForMessages, diag::Report* report);

/// Reads and parses the RIB file at `path`, as ParseRib. A file that cannot be read gives an
/// error at `path`: "cannot read file: reason".
std::optional<SceneDesc> ReadRib(const std::string& path, diag::Report* report);

}  // namespace affray::rib
