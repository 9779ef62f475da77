// texture/texture_map.cpp: TextureMap itself: maps made from pixels, the min/max pyramid (built
// from bands of rows), and RangeOfTexels, which takes an integer rectangle through the wrap modes
// and answers it from exact texel reads when small and from the pyramid when not.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

#include "texture/texture_impl.h"

namespace affray::texture {

using namespace detail;

namespace {

/// Up to two intervals of in-image indices an index interval covers through a wrap mode, and
/// whether it reaches a black texel outside the image.
struct AxisCover {
    int count = 0;
    int lo[2] = {0, 0}, hi[2] = {0, 0};
    bool black = false;
};

AxisCover Cover(int64_t i0, int64_t i1, int size, Wrap wrap) {
    AxisCover a;
    const int64_t n = size;
    switch (wrap) {
        case Wrap::Black:
            a.black = i0 < 0 || i1 >= n;
            if (i1 >= 0 && i0 < n) {
                a.count = 1;
                a.lo[0] = static_cast<int>(std::max<int64_t>(i0, 0));
                a.hi[0] = static_cast<int>(std::min<int64_t>(i1, n - 1));
            }
            break;
        case Wrap::Clamp:
            a.count = 1;
            a.lo[0] = static_cast<int>(std::clamp<int64_t>(i0, 0, n - 1));
            a.hi[0] = static_cast<int>(std::clamp<int64_t>(i1, 0, n - 1));
            break;
        case Wrap::Periodic: {
            // The span as unsigned: i1 - i0 may not fit an int64 (i0 near INT64_MIN, i1 near INT64_MAX).
            const uint64_t span = static_cast<uint64_t>(i1) - static_cast<uint64_t>(i0);
            if (span >= static_cast<uint64_t>(n - 1)) {
                a.count = 1;
                a.lo[0] = 0;
                a.hi[0] = size - 1;
                break;
            }
            int64_t m = i0 % n;
            if (m < 0) m += n;
            const int64_t end = m + static_cast<int64_t>(span);  // < 2n: span < n - 1
            if (end < n) {
                a.count = 1;
                a.lo[0] = static_cast<int>(m);
                a.hi[0] = static_cast<int>(end);
            } else {
                a.count = 2;
                a.lo[0] = static_cast<int>(m);
                a.hi[0] = size - 1;
                a.lo[1] = 0;
                a.hi[1] = static_cast<int>(end - n);
            }
            break;
        }
    }
    return a;
}

}  // namespace

int64_t detail::ZeroNonFinite(float* texels, size_t count) {
    int64_t bad = 0;
    for (size_t i = 0; i < count; ++i) {
        if (!std::isfinite(texels[i])) {
            texels[i] = 0;
            ++bad;
        }
    }
    return bad;
}

// ---- The pyramid ----

PyramidBuilder::PyramidBuilder(int width, int height, int channels) : m_width(width), m_channels(channels) {
    m_level0.width = (width + kBlockSize - 1) >> kBlockBits;
    m_level0.height = (height + kBlockSize - 1) >> kBlockBits;
    const size_t blocks = static_cast<size_t>(m_level0.width) * m_level0.height;
    m_level0.minMax.resize(blocks * channels * 2);
    for (size_t i = 0; i < m_level0.minMax.size(); i += 2) {
        m_level0.minMax[i] = std::numeric_limits<float>::infinity();
        m_level0.minMax[i + 1] = -std::numeric_limits<float>::infinity();
    }
}

void PyramidBuilder::AddRows(int y0, int rows, const float* texels) {
    const size_t bw = m_level0.width, plane = bw * m_level0.height * 2;
    for (int r = 0; r < rows; ++r) {
        const int y = y0 + r;
        const float* row = texels + static_cast<size_t>(r) * m_width * m_channels;
        const size_t blockRow = static_cast<size_t>(y >> kBlockBits) * bw;
        for (int c = 0; c < m_channels; ++c) {
            float* mm = m_level0.minMax.data() + c * plane + blockRow * 2;
            for (int x = 0; x < m_width; ++x) {
                const float v = row[static_cast<size_t>(x) * m_channels + c];
                float* b = mm + static_cast<size_t>(x >> kBlockBits) * 2;
                b[0] = std::min(b[0], v);
                b[1] = std::max(b[1], v);
            }
        }
    }
}

std::vector<PyramidLevel> PyramidBuilder::Finish() {
    std::vector<PyramidLevel> levels;
    levels.push_back(std::move(m_level0));
    // Each level halves the block grid of the one below, to a single block.
    while (levels.back().width > 1 || levels.back().height > 1) {
        const PyramidLevel& below = levels.back();
        PyramidLevel up;
        up.width = (below.width + 1) / 2;
        up.height = (below.height + 1) / 2;
        up.minMax.resize(static_cast<size_t>(up.width) * up.height * m_channels * 2);
        const size_t belowPlane = static_cast<size_t>(below.width) * below.height * 2;
        const size_t upPlane = static_cast<size_t>(up.width) * up.height * 2;
        for (int c = 0; c < m_channels; ++c) {
            const float* src = below.minMax.data() + c * belowPlane;
            float* dst = up.minMax.data() + c * upPlane;
            for (int by = 0; by < up.height; ++by) {
                for (int bx = 0; bx < up.width; ++bx) {
                    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
                    for (int j = 2 * by; j < std::min(2 * by + 2, below.height); ++j) {
                        for (int i = 2 * bx; i < std::min(2 * bx + 2, below.width); ++i) {
                            const float* b = src + (static_cast<size_t>(j) * below.width + i) * 2;
                            lo = std::min(lo, b[0]);
                            hi = std::max(hi, b[1]);
                        }
                    }
                    float* d = dst + (static_cast<size_t>(by) * up.width + bx) * 2;
                    d[0] = lo;
                    d[1] = hi;
                }
            }
        }
        levels.push_back(std::move(up));
    }
    return levels;
}

// ---- The map ----

Range MapImpl::rangeInImage(int x0, int x1, int y0, int y1, int c) const {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    // A small rectangle is read exactly: at most 64 texels, most of them in one tile.
    if (x1 - x0 < 8 && y1 - y0 < 8) {
        for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
                const float v = texel(x, y, c);
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
        }
        return {lo, hi};
    }
    // Otherwise the finest level whose blocks cover the rectangle in a few reads; the blocks may
    // reach past the rectangle, which only widens the range.
    size_t level = 0;
    int bx0 = 0, bx1 = 0, by0 = 0, by1 = 0;
    for (;; ++level) {
        const int shift = kBlockBits + static_cast<int>(level);
        bx0 = x0 >> shift;
        bx1 = x1 >> shift;
        by0 = y0 >> shift;
        by1 = y1 >> shift;
        if (static_cast<int64_t>(bx1 - bx0 + 1) * (by1 - by0 + 1) <= 20 || level + 1 == m_levels.size()) break;
    }
    const PyramidLevel& l = m_levels[level];
    const float* plane = l.minMax.data() + static_cast<size_t>(c) * l.width * l.height * 2;
    for (int by = by0; by <= by1; ++by) {
        for (int bx = bx0; bx <= bx1; ++bx) {
            const float* b = plane + (static_cast<size_t>(by) * l.width + bx) * 2;
            lo = std::min(lo, b[0]);
            hi = std::max(hi, b[1]);
        }
    }
    return {lo, hi};
}

std::shared_ptr<const TextureMap> TextureMap::FromPixels(int width, int height, int channels, std::vector<float> texels,
                                                         Wrap swrap, Wrap twrap, std::string name) {
    // A map of no texels, or of a texel array of the wrong size, is no map: lookups of a null
    // map give the fill value.
    if (width <= 0 || height <= 0 || channels <= 0 ||
        texels.size() != static_cast<size_t>(width) * static_cast<size_t>(height) * static_cast<size_t>(channels))
        return nullptr;
    auto map = std::make_shared<MapImpl>(width, height, channels, std::move(name), swrap, twrap);
    map->setNonFinite(ZeroNonFinite(texels.data(), texels.size()));
    PyramidBuilder builder(width, height, channels);
    builder.AddRows(0, height, texels.data());
    map->m_levels = builder.Finish();
    map->m_pixels = std::move(texels);
    return map;
}

TextureMap::~TextureMap() = default;

float TextureMap::Texel(int x, int y, int c) const { return MapImpl::Of(*this).texel(x, y, c); }

Range TextureMap::RangeOfTexels(int64_t x0, int64_t x1, int64_t y0, int64_t y1, int c, Wrap swrap, Wrap twrap) const {
    if (c < 0 || c >= m_channels || x0 > x1 || y0 > y1) return {0, 0};
    const MapImpl& map = MapImpl::Of(*this);
    const AxisCover ax = Cover(x0, x1, m_width, swrap), ay = Cover(y0, y1, m_height, twrap);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    if (ax.black || ay.black) lo = hi = 0;
    for (int i = 0; i < ax.count; ++i) {
        for (int j = 0; j < ay.count; ++j) {
            const Range r = map.rangeInImage(ax.lo[i], ax.hi[i], ay.lo[j], ay.hi[j], c);
            lo = std::min(lo, r.lo);
            hi = std::max(hi, r.hi);
        }
    }
    return {lo, hi};
}

size_t TextureMap::residentBytes() const {
    const MapImpl& map = MapImpl::Of(*this);
    size_t bytes = map.m_pixels.size() * sizeof(float) + map.m_tileBytes.load(std::memory_order_relaxed);
    for (const PyramidLevel& l : map.m_levels) bytes += l.minMax.size() * sizeof(float);
    return bytes;
}

}  // namespace affray::texture
