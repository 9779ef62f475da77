// renderer/tiling.cpp: tiles of a frame and their header attributes (see tiling.h).
#include "renderer/tiling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace affray::renderer {
namespace {

/// The shortest decimal text of pixel edge `edge` of `res` pixels that the crop rule
/// (CropPixels: ceil(res * ndc - 0.5)) maps back to `edge`: edge / res itself, printed with
/// the fewest significant digits that round trip through that rule.
std::string EdgeText(int edge, int res) {
    const double ndc = static_cast<double>(edge) / res;
    for (int digits = 1; digits <= 17; ++digits) {
        char text[40];
        std::snprintf(text, sizeof text, "%.*g", digits, ndc);
        const double parsed = std::strtod(text, nullptr);
        CameraDesc camera;
        camera.xres = res;
        camera.cropWindow = glm::dvec4(parsed, parsed, 0.0, 1.0);
        if (parsed >= 0 && parsed <= 1 && CropPixels(camera).x0 == edge) return text;
    }
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", ndc);
    return text;
}

bool ParseRange(const std::string& text, PixelRange* range) {
    int v[4];
    char end = 0;
    if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &v[0], &v[1], &v[2], &v[3], &end) != 4) return false;
    *range = {v[0], v[1], v[2], v[3]};
    return true;
}

}  // namespace

std::vector<PixelRange> SplitFrame(int width, int height, int tiles) {
    if (tiles < 1 || width < 1 || height < 1) return {};
    // Rows so that tiles are near square: rows / columns ~ height / width, rows * columns = tiles.
    const double ideal = std::sqrt(static_cast<double>(tiles) * height / width);
    const int rows = std::clamp(static_cast<int>(std::lround(ideal)), 1, std::min(tiles, height));
    std::vector<PixelRange> ranges;
    for (int r = 0; r < rows; ++r) {
        // The first tiles % rows rows take one column more.
        const int columns = tiles / rows + (r < tiles % rows ? 1 : 0);
        if (columns > width) return {};
        const int y0 = static_cast<int>(int64_t(r) * height / rows),
                  y1 = static_cast<int>(int64_t(r + 1) * height / rows);
        for (int c = 0; c < columns; ++c)
            ranges.push_back({static_cast<int>(int64_t(c) * width / columns),
                              static_cast<int>(int64_t(c + 1) * width / columns), y0, y1});
    }
    return ranges;
}

std::string CropWindowText(const PixelRange& range, int width, int height) {
    return EdgeText(range.x0, width) + "," + EdgeText(range.x1, width) + "," + EdgeText(range.y0, height) + "," +
           EdgeText(range.y1, height);
}

void StampTile(const RenderIdentity& frame, const PixelRange& pixels, const std::string& version,
               image::ImageBuffer* image) {
    image->attributes["affray:version"] = version;
    image->attributes["affray:identity"] = frame.Hash();
    image->attributes["affray:scene"] = frame.scene;
    image->attributes["affray:options"] = frame.options;
    image->attributes["affray:pixels"] = std::to_string(pixels.x0) + "," + std::to_string(pixels.x1) + "," +
                                         std::to_string(pixels.y0) + "," + std::to_string(pixels.y1);
}

std::optional<TileHeader> ReadTileHeader(const image::ImageBuffer& image, std::string* error) {
    TileHeader header;
    const std::pair<const char*, std::string*> fields[] = {{"affray:version", &header.version},
                                                           {"affray:identity", &header.identity},
                                                           {"affray:scene", &header.scene},
                                                           {"affray:options", &header.options}};
    for (const auto& [name, slot] : fields) {
        const auto it = image.attributes.find(name);
        if (it == image.attributes.end()) {
            *error = std::string("its header has no ") + name + " attribute (not an image of affray render)";
            return std::nullopt;
        }
        *slot = it->second;
    }
    const auto pixels = image.attributes.find("affray:pixels");
    if (pixels == image.attributes.end() || !ParseRange(pixels->second, &header.pixels)) {
        *error = "its header has no valid affray:pixels attribute (not an image of affray render)";
        return std::nullopt;
    }
    const PixelRange& r = header.pixels;
    if (r.empty() || r.x0 < 0 || r.y0 < 0 || r.x1 > image.width || r.y1 > image.height) {
        *error = "its affray:pixels " + ToString(r) + " lie outside its " + std::to_string(image.width) + "x" +
                 std::to_string(image.height) + " image";
        return std::nullopt;
    }
    return header;
}

}  // namespace affray::renderer
