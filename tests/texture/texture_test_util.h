// tests/texture/texture_test_util.h: what the texture tests share: a temporary directory, images
// written and read back through the image module, OpenImageIO (the reference a map's texels
// must equal), and random small maps for the property tests.
#pragma once

#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "image/image_io.h"
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
using image::io::PixelFormat;
struct ImageLayout : image::io::WriteLayout {
    ImageLayout(PixelFormat f = PixelFormat::Float) { format = f; }
};

/// The image module, which the tests write and read their images through.
inline const image::io::ImageIo& Images() {
    std::string error;
    const image::io::ImageIo* io = image::io::Get(&error);
    INFO(error);
    REQUIRE(io);
    return *io;
}

/// Writes width x height x channels float texels (converted to the layout's format).
inline void WriteImage(const std::string& path, int width, int height, int channels, const std::vector<float>& texels,
                       const ImageLayout& layout = {}) {
    std::string error;
    const bool written = Images().Write(path, width, height, channels, texels.data(), layout, &error);
    INFO(error);
    REQUIRE(written);
}

/// The header of a file as the module reads it.
inline image::io::ImageHeader ReadHeader(const std::string& path) {
    std::string error;
    auto in = Images().Open(path, &error);
    INFO(error);
    REQUIRE(in);
    return in->header();
}

/// Level 0 of subimage 0 as OIIO reads it in float: the reference for a map's texels.
inline std::vector<float> ReadImage(const std::string& path, int* width, int* height, int* channels) {
    std::string error;
    auto in = Images().Open(path, &error);
    INFO(error);
    REQUIRE(in);
    const image::io::ImageHeader h = in->header();
    *width = h.width;
    *height = h.height;
    *channels = h.channels;
    std::vector<float> texels(static_cast<size_t>(h.width) * h.height * h.channels);
    if (h.tileWidth == 0) {
        REQUIRE(in->readScanlines(0, h.height, texels.data()));
    } else {
        REQUIRE(in->readTiles(0, h.width, 0, h.height, texels.data()));
    }
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
