// image/png_writer.cpp: the smallest correct PNG: IHDR, one zlib-compressed IDAT of unfiltered
// scanlines, IEND (PNG specification, ISO/IEC 15948), chunk CRCs from zlib.
#include "image/png_writer.h"

#include "image/atomic_file.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace affray::image {

namespace {

void PutU32(std::vector<unsigned char>& out, uint32_t x) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>(x >> shift));
}

void PutChunk(std::vector<unsigned char>& out, const char* type, const std::vector<unsigned char>& data) {
    PutU32(out, static_cast<uint32_t>(data.size()));
    size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    uLong crc = crc32(0L, out.data() + start, static_cast<uInt>(out.size() - start));
    PutU32(out, static_cast<uint32_t>(crc));
}

unsigned char ToSrgb8(float linear) {
    double c = std::clamp(static_cast<double>(linear), 0.0, 1.0);
    double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
    return static_cast<unsigned char>(std::lround(s * 255));
}

}  // namespace

bool WritePngPreview(const std::string& path, const ImageBuffer& image, diag::Report* report) {
    auto fail = [&](const std::string& reason) {
        if (report) report->error({path}, "cannot write file: " + reason);
        return false;
    };
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4)
        return fail("empty or malformed image");
    std::vector<unsigned char> raw;
    raw.reserve((static_cast<size_t>(image.width) * 4 + 1) * image.height);
    for (int y = 0; y < image.height; ++y) {
        raw.push_back(0);  // filter type: none
        for (int x = 0; x < image.width; ++x) {
            const float* p = &image.rgba[(static_cast<size_t>(y) * image.width + x) * 4];
            for (int c = 0; c < 3; ++c) raw.push_back(ToSrgb8(p[c]));
            raw.push_back(static_cast<unsigned char>(std::lround(std::clamp(p[3], 0.0f, 1.0f) * 255)));
        }
    }
    uLongf packedSize = compressBound(static_cast<uLong>(raw.size()));
    std::vector<unsigned char> packed(packedSize);
    if (compress2(packed.data(), &packedSize, raw.data(), static_cast<uLong>(raw.size()), 6) != Z_OK)
        return fail("compression failed");
    packed.resize(packedSize);

    std::vector<unsigned char> file = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<unsigned char> header;
    PutU32(header, static_cast<uint32_t>(image.width));
    PutU32(header, static_cast<uint32_t>(image.height));
    header.insert(header.end(), {8, 6, 0, 0, 0});  // 8 bits, RGBA, deflate, no filter, no interlace
    PutChunk(file, "IHDR", header);
    PutChunk(file, "IDAT", packed);
    PutChunk(file, "IEND", {});

    std::string reason;
    if (!WriteFileAtomically(path, std::string_view(reinterpret_cast<const char*>(file.data()), file.size()), &reason))
        return fail(reason);
    return true;
}

}  // namespace affray::image
