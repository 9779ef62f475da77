// tools/merge.cpp: `affray merge OUT.exr TILE.exr...`, the tiles of one frame rendered by separate
// processes (affray split) pasted into one image, bit for bit the image one process renders.
// Before anything is written it checks, from each tile's header (renderer/tiling.h), that the
// tiles come from one render (same affray version, scene and options, crop left out), have the
// same size and channels, and cover the frame exactly once; each refusal names the tile files and
// exits 1 with nothing written. The image is written atomically (image/atomic_file.h).
// Only the headers are read for the checks; then each tile's own band of rows is read and pasted
// in turn, so merging holds the whole image and one band, not every tile.
#include <algorithm>
#include <cstdint>
#include <optional>

#include "image/exr_writer.h"
#include "renderer/tiling.h"
#include "tools/commands.h"

namespace affray::tools {
namespace {

struct Tile {
    std::string path;
    image::ImageBuffer image;  // header: size, attributes, channel names (no pixels)
    renderer::TileHeader header;
};

std::string Channels(const image::ImageBuffer& image) {
    std::string names = "R,G,B,A";
    for (const auto& channel : image.extraChannels) names += "," + channel.first;
    return names;
}

/// Why tile `b` cannot be merged with tile `a` (one render, one size, one channel list), or "".
std::string Mismatch(const Tile& a, const Tile& b) {
    const image::ImageBuffer &ia = a.image, &ib = b.image;
    if (b.header.version != a.header.version)
        return "tiles of different affray versions: " + b.path + " was rendered by affray " + b.header.version + ", " +
               a.path + " by affray " + a.header.version;
    if (const std::string names = renderer::DifferingOptions(a.header.options, b.header.options); !names.empty())
        return "tiles of different options: " + b.path + " and " + a.path + " were rendered with different " + names;
    if (b.header.scene != a.header.scene || b.header.identity != a.header.identity)
        return "tiles of different scenes: " + b.path + " and " + a.path +
               " were rendered from different scenes (the RIB file, a shader or a texture differs)";
    if (ib.width != ia.width || ib.height != ia.height)
        return "tiles of different sizes: " + b.path + " is " + std::to_string(ib.width) + "x" +
               std::to_string(ib.height) + ", " + a.path + " is " + std::to_string(ia.width) + "x" +
               std::to_string(ia.height);
    if (Channels(ib) != Channels(ia))
        return "tiles of different channels: " + b.path + " has " + Channels(ib) + ", " + a.path + " has " +
               Channels(ia);
    return "";
}

/// The pixels both ranges cover.
renderer::PixelRange Overlap(const renderer::PixelRange& a, const renderer::PixelRange& b) {
    return {std::max(a.x0, b.x0), std::min(a.x1, b.x1), std::max(a.y0, b.y0), std::min(a.y1, b.y1)};
}

}  // namespace

int RunMerge(const MergeCommand& cmd, FILE* /*out*/, FILE* err) {
    diag::Report report;
    auto refuse = [&](const std::string& where, const std::string& message) {
        report.error({where}, message + "; nothing written");
        Print(report, err);
        return diag::kExitBadInput;
    };
    // Read every tile's header.
    std::vector<Tile> tiles;
    for (const std::string& path : cmd.tiles) {
        Tile tile{path, {}, {}};
        if (!image::ReadExrHeader(path, &tile.image, &report)) {
            Print(report, err);
            return diag::kExitBadInput;
        }
        std::string why;
        std::optional<renderer::TileHeader> header = renderer::ReadTileHeader(tile.image, &why);
        if (!header) return refuse(path, "not a tile: " + why);
        tile.header = *header;
        tiles.push_back(std::move(tile));
    }
    // One render, one size, one channel list.
    for (size_t i = 1; i < tiles.size(); ++i)
        if (const std::string why = Mismatch(tiles[0], tiles[i]); !why.empty()) return refuse(tiles[i].path, why);
    // The frame covered exactly once: no two tiles overlap, and together they cover every pixel.
    for (size_t i = 0; i < tiles.size(); ++i)
        for (size_t j = 0; j < i; ++j)
            if (const renderer::PixelRange both = Overlap(tiles[j].header.pixels, tiles[i].header.pixels);
                !both.empty())
                return refuse(tiles[i].path, "overlapping tiles: " + tiles[i].path + " and " + tiles[j].path +
                                                 " both cover the pixels " + renderer::ToString(both));
    const int width = tiles[0].image.width, height = tiles[0].image.height;
    int64_t covered = 0;
    for (const Tile& tile : tiles) {
        const renderer::PixelRange& r = tile.header.pixels;
        covered += int64_t(r.x1 - r.x0) * (r.y1 - r.y0);
    }
    if (covered != int64_t(width) * height) {
        // The bounding box of the pixels no tile covers, to say where the missing tile goes.
        std::vector<uint8_t> inTile(size_t(width) * height, 0);
        for (const Tile& tile : tiles)
            for (int y = tile.header.pixels.y0; y < tile.header.pixels.y1; ++y)
                std::fill_n(inTile.begin() + int64_t(y) * width + tile.header.pixels.x0,
                            tile.header.pixels.x1 - tile.header.pixels.x0, 1);
        renderer::PixelRange missing{width, 0, height, 0};
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                if (!inTile[size_t(y) * width + x])
                    missing = {std::min(missing.x0, x), std::max(missing.x1, x + 1), std::min(missing.y0, y),
                               std::max(missing.y1, y + 1)};
        return refuse(cmd.outputPath, "missing tile: " + std::to_string(int64_t(width) * height - covered) + " of " +
                                          std::to_string(int64_t(width) * height) + " pixels (within " +
                                          renderer::ToString(missing) + ") are in none of the " +
                                          std::to_string(tiles.size()) + " tiles given");
    }
    // Paste each tile's band of rows in turn; the header is the one a single render of the frame
    // writes, and the channels are in the tiles' order.
    image::ImageBuffer whole{width, height, std::vector<float>(size_t(width) * height * 4, 0.0f), {}, {}};
    for (const auto& channel : tiles[0].image.extraChannels)
        whole.extraChannels.emplace_back(channel.first, std::vector<float>(size_t(width) * height, 0.0f));
    for (const Tile& tile : tiles) {
        const renderer::PixelRange& r = tile.header.pixels;
        image::ImageBuffer band;
        if (!image::ReadExrRgba(tile.path, &band, &report, std::array<int, 2>{r.y0, r.y1})) {
            Print(report, err);
            return diag::kExitBadInput;
        }
        if (Channels(band) != Channels(tile.image) || band.width != width)
            return refuse(tile.path, "the file changed while merging");
        for (int y = r.y0; y < r.y1; ++y) {
            const size_t from = size_t(y - r.y0) * width + r.x0, to = size_t(y) * width + r.x0;
            const size_t n = size_t(r.x1 - r.x0);
            std::copy_n(band.rgba.begin() + int64_t(from * 4), n * 4, whole.rgba.begin() + int64_t(to * 4));
            for (size_t c = 0; c < band.extraChannels.size(); ++c)
                std::copy_n(band.extraChannels[c].second.begin() + int64_t(from), n,
                            whole.extraChannels[c].second.begin() + int64_t(to));
        }
    }
    whole.attributes = tiles[0].image.attributes;
    whole.attributes["affray:pixels"] = "0," + std::to_string(width) + ",0," + std::to_string(height);
    if (!image::WriteExr(cmd.outputPath, whole, &report)) {
        Print(report, err);
        return diag::kExitOutput;
    }
    return diag::kExitSuccess;
}

}  // namespace affray::tools
