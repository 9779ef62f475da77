// tests/texture/texture_test_util.h: what the texture tests share: a temporary directory, images
// written and read back through OpenImageIO (the reference a map's texels must equal), and random
// small maps for the property tests.
#pragma once

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/test_random.h"
#include "texture/texture.h"

namespace affray::test::tex {

/// A directory of its own under the system's temporary directory, removed with its files.
class ScratchDir {
  public:
    ScratchDir() {
        static std::atomic<int> counter{0};
        m_path = std::filesystem::temp_directory_path() /
                 ("affray-texture-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
        std::filesystem::create_directories(m_path);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    std::string path(const std::string& name) const { return (m_path / name).string(); }

  private:
    std::filesystem::path m_path;
};

/// How an image is laid out in its file.
struct ImageLayout {
    ImageLayout(const OIIO::TypeDesc& f = OIIO::TypeDesc::FLOAT) : format(f) {}
    OIIO::TypeDesc format;
    int tile = 0;         // tile size, 0 for scanlines
    bool mipmap = false;  // write the coarser levels too (a .tx-like file)
    std::string wrapmodes;
};

/// Writes width x height x channels float texels (converted to the layout's format by OIIO).
inline void WriteImage(const std::string& path, int width, int height, int channels, const std::vector<float>& texels,
                       const ImageLayout& layout = {}) {
    auto out = OIIO::ImageOutput::create(path);
    REQUIRE(out);
    OIIO::ImageSpec spec(width, height, channels, layout.format);
    if (layout.tile) spec.tile_width = spec.tile_height = layout.tile;
    if (!layout.wrapmodes.empty()) spec.attribute("wrapmodes", layout.wrapmodes);
    // OIIO's TIFF writer takes no MIP levels as such: like maketx, it writes them as subimages
    // of a "Plain Texture", which its reader reads as MIP levels.
    const bool asMipLevels = out->supports("mipmap");
    REQUIRE((!layout.mipmap || asMipLevels || out->supports("multiimage")));
    if (layout.mipmap && !asMipLevels) spec.attribute("textureformat", "Plain Texture");
    const bool mipmap = layout.mipmap;
    REQUIRE(out->open(path, spec));
    REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, texels.data()));
    if (mipmap) {
        // Each coarser level a box-filtered half of the one before, down to 1x1.
        std::vector<float> level = texels;
        int w = width, h = height;
        while (w > 1 || h > 1) {
            const int nw = std::max(1, w / 2), nh = std::max(1, h / 2);
            std::vector<float> next(static_cast<size_t>(nw) * nh * channels);
            for (int y = 0; y < nh; ++y)
                for (int x = 0; x < nw; ++x)
                    for (int c = 0; c < channels; ++c)
                        next[(static_cast<size_t>(y) * nw + x) * channels + c] =
                            level[(static_cast<size_t>(std::min(2 * y, h - 1)) * w + std::min(2 * x, w - 1)) *
                                      channels +
                                  c];
            OIIO::ImageSpec s(nw, nh, channels, layout.format);
            if (layout.tile) s.tile_width = s.tile_height = layout.tile;
            if (!asMipLevels) s.attribute("textureformat", "Plain Texture");
            REQUIRE(out->open(path, s,
                              asMipLevels ? OIIO::ImageOutput::AppendMIPLevel : OIIO::ImageOutput::AppendSubimage));
            REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, next.data()));
            level = std::move(next);
            w = nw;
            h = nh;
        }
    }
    REQUIRE(out->close());
}

/// Level 0 of subimage 0 as OIIO reads it in float: the reference for a map's texels.
inline std::vector<float> ReadImage(const std::string& path, int* width, int* height, int* channels) {
    auto in = OIIO::ImageInput::open(path);
    REQUIRE(in);
    const OIIO::ImageSpec spec = in->spec(0, 0);
    *width = spec.width;
    *height = spec.height;
    *channels = spec.nchannels;
    std::vector<float> texels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    REQUIRE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, texels.data()));
    return texels;
}

/// Random texels in [-2, 2], some of them repeated, some small integers.
inline std::vector<float> RandomTexels(Rng& rng, size_t count) {
    std::vector<float> t(count);
    for (float& v : t) {
        const int kind = rng.integer(0, 3);
        v = kind == 0 ? static_cast<float>(rng.integer(-2, 2)) : static_cast<float>(rng.uniform(-2, 2));
    }
    return t;
}

inline texture::Wrap RandomWrap(Rng& rng) { return static_cast<texture::Wrap>(rng.integer(0, 2)); }

}  // namespace affray::test::tex
