// image/exr_writer.h: an image buffer (what the renderer's film fills) and its OpenEXR file I/O.
// Owns the on-disk format of rendered images: RGBA as HALF, any extra channels (Z, AOVs) as
// FLOAT, scanline order with row 0 at the top. Writes are atomic: the image goes to a temporary
// file beside the target and is renamed onto it, so a reader never sees a half-written image.
// Failures are reported as errors at the file (diag/diagnostic.h): "cannot write file: reason";
// nothing throws.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "diag/diagnostic.h"

namespace affray::image {

/// A float image: interleaved RGBA plus optional named float channels.
struct ImageBuffer {
    int width = 0, height = 0;
    std::vector<float> rgba;  ///< Interleaved RGBA, width * height * 4, row 0 at the top.
    /// Extra float32 channels such as {"Z", ...}, width * height values each, same pixel order.
    std::vector<std::pair<std::string, std::vector<float>>> extraChannels;
    /// String attributes of the file's header, such as the render's identity that affray merge
    /// checks ("affray:identity", renderer/tiling.h). Read back: every string attribute.
    std::map<std::string, std::string> attributes;
};

/// Describes an image on one line ("640x480 RGBA + Z"), for logs.
std::string ToString(const ImageBuffer& image);

/// Writes `image` to `path` as OpenEXR, atomically (temporary file in the same directory, then
/// rename). Returns false, with an error in *report (may be null) and no temporary file left
/// behind, if the image is malformed (sizes, channel names) or the file cannot be written.
bool WriteExr(const std::string& path, const ImageBuffer& image, diag::Report* report);

/// Reads an OpenEXR file: R, G, B, A into out->rgba (missing color channels read as 0, a missing
/// alpha as 1) and every other channel into out->extraChannels, as float. Returns false with an
/// error at `path` in *report (may be null), "cannot read image: reason", on failure.
/// With `rows` = {y0, y1}, reads only the rows y0 to y1 - 1: *out is then width x (y1 - y0), its
/// row 0 the file's row y0 (a tile of a frame rendered in parts, affray merge, reads only its own
/// band of rows, and holds no more).
bool ReadExrRgba(const std::string& path, ImageBuffer* out, diag::Report* report,
                 std::optional<std::array<int, 2>> rows = std::nullopt);

/// Reads only the header of an OpenEXR file: out->width, height and attributes, and
/// out->extraChannels with their names and no values. Errors as ReadExrRgba.
bool ReadExrHeader(const std::string& path, ImageBuffer* out, diag::Report* report);

}  // namespace affray::image
