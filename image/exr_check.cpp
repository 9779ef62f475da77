// image/exr_check.cpp: the header check of image/exr_check.h.
#include "image/exr_check.h"

#include <cstdint>
#include <fstream>

namespace affray::image {

std::string OversizedExrHeader(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    unsigned char head[8] = {};
    if (!in.read(reinterpret_cast<char*>(head), 8)) return "";
    if (!(head[0] == 0x76 && head[1] == 0x2f && head[2] == 0x31 && head[3] == 0x01)) return "";
    const bool multipart = (head[5] & 0x10) != 0;
    in.seekg(0, std::ios::end);
    const auto size = static_cast<uint64_t>(in.tellg());
    in.seekg(8);
    const char* const early = "the OpenEXR header ends before the end of its attributes";
    // A name or type: up to 255 characters and a terminating 0.
    auto word = [&](std::string* out) {
        out->clear();
        for (char c; in.get(c);) {
            if (c == '\0') return true;
            if (out->size() == 255) return false;
            out->push_back(c);
        }
        return false;
    };
    for (int part = 0;; ++part) {
        if (part > 0) {
            // Multi-part files: headers follow one another, and an empty one ends them.
            const int next = in.peek();
            if (next == std::char_traits<char>::eof()) return early;
            if (next == 0) return "";
        }
        for (std::string name, type;;) {
            if (!word(&name)) return early;
            if (name.empty()) break;
            unsigned char bytes[4];
            if (!word(&type) || !in.read(reinterpret_cast<char*>(bytes), 4)) return early;
            const uint64_t length =
                uint64_t{bytes[0]} | uint64_t{bytes[1]} << 8 | uint64_t{bytes[2]} << 16 | uint64_t{bytes[3]} << 24;
            const auto at = static_cast<uint64_t>(in.tellg());
            if (length > size - at)
                return "the OpenEXR attribute '" + name + "' claims " + std::to_string(length) +
                       " bytes, but the file has " + std::to_string(size - at) + " left";
            in.seekg(static_cast<std::streamoff>(at + length));
        }
        if (!multipart) return "";
    }
}

}  // namespace affray::image
