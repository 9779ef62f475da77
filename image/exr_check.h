// image/exr_check.h: a check of an OpenEXR file's headers before OpenEXR reads them.
// Debian's OpenEXR 3.1 allocates an attribute's stated size before it reads the attribute, so a
// 15 KB file that claims a 2 GB string takes 2 GB before it is refused (found by fuzz_texture;
// fuzz/regressions/fuzz_texture holds the input). Every reader of EXR files an affray user gives
// calls this first: texture maps (through OpenImageIO, in the image-file module, which compiles
// its own copy of exr_check.cpp) and the tiles of `affray merge` (exr_writer.cpp).
#pragma once

#include <string>

namespace affray::image {

/// Why the OpenEXR file at `path` cannot be read, or "" when its headers are sound or it is not
/// an OpenEXR file: every attribute of every header (one per part) must fit in the file, with
/// names and types no longer than OpenEXR reads them, values of fixed-size types in their size,
/// and channel lists, previews and string vectors holding what they say (image/exr_check.cpp).
std::string OversizedExrHeader(const std::string& path);

}  // namespace affray::image
