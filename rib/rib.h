// rib/rib.h: reading a RIB file into a SceneDesc.
// The reader follows the RenderMan Interface Specification 3.2 for the requests it implements:
// options (Format, Projection, FrameAspectRatio, ScreenWindow, CropWindow, Clipping, PixelSamples,
// PixelFilter box/gaussian, Exposure, Display with its mode checked, Hider "hidden" "jitter",
// Option "searchpath" "shader", "texture" and "archive"), Declare and inline declarations on every parameter
// list, transforms and Begin/End scopes, CoordinateSystem, CoordSysTransform, attributes (Color,
// Opacity 1 1 1, Surface constant/matte/metal/plastic, Displacement, Sides, ReverseOrientation,
// Orientation, Illuminate on),
// lights (ambientlight, distantlight, pointlight, spotlight), ReadArchive, retained objects
// (ObjectBegin, ObjectEnd, ObjectInstance) and geometry (bilinear Patch, Sphere, Cylinder, Cone,
// Disk, Torus, Hyperboloid, Paraboloid). Other RI 3.2 requests (and those of later RenderMan
// versions that exporters write), other Option and Attribute names, other hiders and unknown
// shaders are skipped with one warning per name, as are primitives affray cannot make (the image
// lacks them): see rib/unsupported.cpp. Perspective is the camera's projection where it is one
// (first in the camera transform), else an error, as is a name that is no request. Problems are reported through
// diag/diagnostic.h, at the file (the scene or an archive), line and column of the token.
//
// Frames: each world block is one frame, a SceneDesc. Options before the first FrameBegin are
// defaults for every frame; options, lights and coordinate systems given inside a frame last
// until its FrameEnd. A frame that only makes a shadow or depth map for a scanline renderer
// (Display type "zfile", "shadow" or "deepshadow", or mode "z" to a file that is not OpenEXR)
// is read, checked and marked skipped, with a note; so are MakeShadow and the other Make*
// requests but MakeTexture, which every later frame records (SceneDesc::makeTextures).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "diag/diagnostic.h"
#include "scene/scene.h"

namespace affray::rib {

using renderer::SceneDesc;

/// Parses RIB text into its frames, in file order (one for a file without FrameBegin), skipped
/// frames included (SceneDesc::skipped says why; their primitives are dropped). Each scene has
/// path = pathForMessages. Warnings and notes go to *report (may be null). On failure returns
/// nullopt with the first error in *report; parsing stops there. Never throws on bad input.
std::optional<std::vector<SceneDesc>> ParseRibFrames(std::string_view text, const std::string& pathForMessages,
                                                     diag::Report* report);

/// Reads and parses the RIB file at `path`, as ParseRibFrames. A file that cannot be read gives an
/// error at `path`: "cannot read file: reason".
std::optional<std::vector<SceneDesc>> ReadRibFrames(const std::string& path, diag::Report* report);

/// ParseRibFrames for callers that render one image: the first frame that is not skipped. A file
/// whose every frame is skipped is an error at `pathForMessages`.
std::optional<SceneDesc> ParseRib(std::string_view text, const std::string& pathForMessages, diag::Report* report);

/// ReadRibFrames's first frame that is not skipped, as ParseRib.
std::optional<SceneDesc> ReadRib(const std::string& path, diag::Report* report);

}  // namespace affray::rib
