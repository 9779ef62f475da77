// renderer/tiling.h: a frame cut into tiles that separate processes render (affray split), and
// what each tile's OpenEXR header says about the render it belongs to, so that the tiles can be
// checked and pasted back together bit for bit (affray merge).
//
// Tiles are exact pixel rectangles that cover the frame once. Each is rendered with a crop window
// (renderer/film.h, CropPixels) chosen so that it maps to exactly that rectangle.
//
// Header attributes (string attributes of every image affray render writes, ImageBuffer::attributes):
//   affray:version   the affray version that rendered it ("0.1.0")
//   affray:identity  RenderIdentity::Hash() of IdentifyFrame: scene and options, crop left out
//   affray:scene     RenderIdentity::scene of IdentifyFrame (32 hex digits)
//   affray:options   RenderIdentity::options of IdentifyFrame (no crop line)
//   affray:pixels    the pixel rectangle the image covers, "x0,x1,y0,y1" (x1, y1 past the end);
//                    the whole frame for an image that is not a crop
// The frame's size is the image's. Adding an attribute: name it "affray:...", write it in
// StampTile and read it in ReadTileHeader.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "image/exr_writer.h"
#include "renderer/film.h"
#include "renderer/render_identity.h"

namespace affray::renderer {

/// Cuts a width x height frame into `tiles` rectangles that cover it exactly once: rows of
/// near-square tiles, row by row from the top left. Empty if tiles < 1 or the frame has fewer
/// pixels than a rows x columns layout needs.
std::vector<PixelRange> SplitFrame(int width, int height, int tiles);

/// A crop window "XMIN,XMAX,YMIN,YMAX" (as `affray render --crop` reads it) whose pixels at
/// width x height are exactly `range` (CropPixels), with the fewest digits that do so.
std::string CropWindowText(const PixelRange& range, int width, int height);

/// What the header of a rendered image says (the attributes of the file comment).
struct TileHeader {
    std::string version, identity, scene, options;
    PixelRange pixels;
};

/// Sets the header attributes of `image`, the render of `pixels` of the frame identified by
/// `frame` (IdentifyFrame), by affray `version`.
void StampTile(const RenderIdentity& frame, const PixelRange& pixels, const std::string& version,
               image::ImageBuffer* image);

/// Reads the header attributes of `image`; nullopt with *error (one phrase) if one is missing or
/// malformed, or the pixels lie outside the image.
std::optional<TileHeader> ReadTileHeader(const image::ImageBuffer& image, std::string* error);

}  // namespace affray::renderer
