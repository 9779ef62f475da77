// renderer/rib.h: reading a RIB file into a SceneDesc.
// The reader follows the RenderMan Interface Specification 3.2 for the requests it implements
// (camera, transforms, attribute scopes, lights, plastic/matte surfaces, displacement shaders,
// bilinear patches). Other RI 3.2 requests are skipped with one warning per request name, unless
// ignoring them would change the geometry (other primitives, Skew, Perspective, MotionBegin, ...),
// which is an error. Messages are "file:line: error: message" / "file:line: warning: message".
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/scene.h"

namespace affray::renderer {

/// Parses RIB text. On success returns the scene (with path = pathForMessages) and appends any
/// warnings to *warnings (may be null). On failure returns nullopt and sets *error (may be null)
/// to the first error, "file:line: error: message"; parsing stops there. Never throws on bad input.
std::optional<SceneDesc> ParseRib(std::string_view text, const std::string& pathForMessages,
                                  std::string* error, std::vector<std::string>* warnings);

/// Reads and parses the RIB file at `path`, as ParseRib. A file that cannot be read gives
/// "path: error: cannot read file: reason".
std::optional<SceneDesc> ReadRib(const std::string& path, std::string* error,
                                 std::vector<std::string>* warnings);

}  // namespace affray::renderer
