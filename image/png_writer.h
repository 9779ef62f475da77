// image/png_writer.h: an 8-bit sRGB PNG preview of a rendered image (for READMEs, quick looks
// and the `--png` option); the OpenEXR file stays the real output.
#pragma once

#include <string>

#include "image/exr_writer.h"

namespace affray::image {

/// Writes `image`'s RGBA as an 8-bit PNG: colours clamped to [0,1] and sRGB-encoded, alpha kept.
/// Written atomically like WriteExr (temporary file, then rename); failures are reported like
/// WriteExr's.
bool WritePngPreview(const std::string& path, const ImageBuffer& image, diag::Report* report);

}  // namespace affray::image
