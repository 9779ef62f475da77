// fuzz/fuzz_texture.cpp: image file bytes -> OpenImageIO (in libaffray_image_io.so) -> a texture
// map as texture() opens one (header checks, the min/max pyramid built from bands of rows) ->
// texels, ranges and lookups read through its tiles.
// The bytes are written to a file without an extension: the image module picks the one reader
// their signature names (image/image_io_oiio.cpp, FormatOf), or refuses them. An image whose header
// asks for more than kMaxTexels texels (and that the map would accept: sides and tile counts up
// to 2^30) is skipped before the map reads it: the map allocates as the header says, and reads
// and checks every texel for its pyramid, about 0.2 us a texel under the sanitizers, so that a
// run stays well within a few milliseconds (a 256 x 256 map: 13 ms) and the memory limit.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "fuzz/fuzz_util.h"
#include "image/image_io.h"
#include "texture/texture.h"

namespace {

constexpr int64_t kMaxTexels = int64_t{1} << 16;
constexpr int64_t kMaxSide = int64_t{1} << 30;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace affray;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::string path = fuzz::WriteTemp("input", bytes);
    std::string error;
    const image::io::ImageIo* images = image::io::Get(&error);
    if (!images) {
        std::fprintf(stderr, "fuzz_texture: %s\n", error.c_str());
        std::abort();
    }
    {
        std::unique_ptr<image::io::ImageReader> reader = images->Open(path, &error);
        if (!reader) return 0;
        const image::io::ImageHeader& h = reader->header();
        const bool accepted =
            h.width > 0 && h.height > 0 && h.channels > 0 && h.width <= kMaxSide && h.height <= kMaxSide;
        if (accepted && int64_t{h.width} * h.height * h.channels > kMaxTexels) return 0;
    }
    std::shared_ptr<const texture::TextureMap> map = texture::Open(path, &error);
    if (!map) return 0;
    const int w = map->width(), h = map->height();
    for (int c = 0; c < map->channels(); ++c) {
        map->Texel(0, 0, c);
        map->Texel(w - 1, h - 1, c);
        map->Texel(w / 2, h / 2, c);
        map->RangeOfTexels(-1, w, -1, h, c, texture::Wrap::Periodic, texture::Wrap::Clamp);
    }
    texture::LookupOptions options;
    for (texture::Filter filter : {texture::Filter::Box, texture::Filter::Gaussian}) {
        options.filter = filter;
        options.sblur = filter == texture::Filter::Box ? 0.0 : 0.1;
        texture::Sample(map.get(), options, 0, 0.3, 0.7);
        double dds = 0, ddt = 0;
        texture::SampleGrad(map.get(), options, 0, 0.9, 0.1, &dds, &ddt);
        texture::RangeOver(map.get(), options, 0, {0.1, 0.6}, {0.2, 0.4});
    }
    return 0;
}
