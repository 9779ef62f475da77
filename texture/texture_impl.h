// texture/texture_impl.h: the private side of texture.h shared by the library's sources: the one
// concrete map class (texels resident or in tiles read from a file), its min/max pyramid, and the
// texel access every lookup goes through. Not part of the library's interface.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "texture/texture.h"

namespace affray::texture::detail {

/// Texels of a file map are read in square tiles of kTileSize texels (all channels, float).
inline constexpr int kTileBits = 6;
inline constexpr int kTileSize = 1 << kTileBits;
/// Level 0 of the pyramid holds the min and max over blocks of kBlockSize x kBlockSize texels.
inline constexpr int kBlockBits = 2;
inline constexpr int kBlockSize = 1 << kBlockBits;

/// A tile of level-0 texels: width x height texels (less than kTileSize at the right and bottom
/// edges), channels interleaved. Immutable once read, so a thread may keep using one after the
/// cache has dropped it.
struct Tile {
    int width = 0, height = 0;
    std::vector<float> texels;
};

/// One level of the min/max pyramid: blocks of (kBlockSize << level) texels, per channel a plane
/// of width x height blocks holding (min, max) pairs.
struct PyramidLevel {
    int width = 0, height = 0;
    std::vector<float> minMax;  // [channel][by][bx][2]
};

/// Builds the pyramid from bands of rows, so a file never has to be resident at once.
class PyramidBuilder {
  public:
    PyramidBuilder(int width, int height, int channels);
    /// Rows [y0, y0 + rows) of full width, channels interleaved, already finite. y0 is a multiple of
    /// kBlockSize, and so is `rows` unless the band ends the image.
    void AddRows(int y0, int rows, const float* texels);
    /// The finished levels, level 0 first, the last one a single block.
    std::vector<PyramidLevel> Finish();

  private:
    int m_width, m_channels;
    PyramidLevel m_level0;
};

/// Replaces NaN and infinite texels by 0; returns how many there were.
int64_t ZeroNonFinite(float* texels, size_t count);

class FileSource;  // texture_file.cpp: the open image and its tile slots

/// The only kind of TextureMap: every TextureMap the library hands out is a MapImpl.
class MapImpl final : public TextureMap {
  public:
    MapImpl(int width, int height, int channels, std::string name, Wrap swrap, Wrap twrap);
    ~MapImpl() override;

    static const MapImpl& Of(const TextureMap& map) { return static_cast<const MapImpl&>(map); }

    void setNonFinite(int64_t n) { m_nonFinite = n; }

    /// Texel (x, y) of channel c, indices inside the image. Without a lock on the common path:
    /// resident texels, or the tile from the calling thread's small cache.
    float texel(int x, int y, int c) const {
        if (!m_pixels.empty())
            return m_pixels[(static_cast<size_t>(y) * m_width + static_cast<size_t>(x)) * m_channels + c];
        const Tile* tile = threadTile((y >> kTileBits) * m_tilesX + (x >> kTileBits));
        return tile
            ->texels[(static_cast<size_t>(y & (kTileSize - 1)) * tile->width + (x & (kTileSize - 1))) * m_channels + c];
    }
    /// The least and greatest texel of channel c over [x0, x1] x [y0, y1] inside the image.
    Range rangeInImage(int x0, int x1, int y0, int y1, int c) const;

    uint64_t id() const { return m_id; }
    int tilesX() const { return m_tilesX; }
    int tilesY() const { return m_tilesY; }

    std::vector<float> m_pixels;         // every texel, for a map made from pixels
    std::vector<PyramidLevel> m_levels;  // the min/max pyramid
    std::unique_ptr<FileSource> m_source;
    std::atomic<size_t> m_tileBytes{0};  // resident tiles of this map

  private:
    /// The tile of the given index (texture_file.cpp), through the thread's cache.
    const Tile* threadTile(int index) const;

    uint64_t m_id;
    int m_tilesX, m_tilesY;
};

/// The four-corner lookup's taps, in the order SampleQuad sums them: the kQuadTaps x kQuadTaps
/// points (u, v) = ((i + 0.5) / kQuadTaps, (j + 0.5) / kQuadTaps) of the bilinear quadrilateral of
/// the corners (1 and 2 along s, then 3 and 4). visit(ps, pt, w) gets each tap's place and the
/// corners' bilinear weights there.
template <class Visit>
void ForEachQuadTap(const double s[4], const double t[4], Visit&& visit) {
    for (int j = 0; j < kQuadTaps; ++j) {
        const double v = (j + 0.5) / kQuadTaps;
        for (int i = 0; i < kQuadTaps; ++i) {
            const double u = (i + 0.5) / kQuadTaps;
            const double ps = (1 - v) * ((1 - u) * s[0] + u * s[1]) + v * ((1 - u) * s[2] + u * s[3]);
            const double pt = (1 - v) * ((1 - u) * t[0] + u * t[1]) + v * ((1 - u) * t[2] + u * t[3]);
            const double w[4] = {(1 - v) * (1 - u), (1 - v) * u, v * (1 - u), v * u};
            visit(ps, pt, w);
        }
    }
}

}  // namespace affray::texture::detail
