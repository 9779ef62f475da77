// image/exr_check.cpp: the header check of image/exr_check.h.
#include "image/exr_check.h"

#include <cstdint>
#include <fstream>
#include <string>

namespace affray::image {
namespace {

/// The little-endian 32-bit number at `p` (OpenEXR's sizes and numbers).
uint32_t Le32(const void* p) {
    const auto* b = static_cast<const unsigned char*>(p);
    return uint32_t{b[0]} | uint32_t{b[1]} << 8 | uint32_t{b[2]} << 16 | uint32_t{b[3]} << 24;
}

/// Why a channel list's `value` is refused, or "". OpenEXR reads the entries from the stream until
/// an empty name, whatever the attribute's size says, and stores a pixel type it does not know,
/// on which OpenImageIO's reader (2.4, built with assertions) aborts the process (found by
/// fuzz_texture): so the entries must fill the value exactly, each with a pixel type of 0-2.
std::string BadChannelList(const std::string& value) {
    size_t at = 0;
    for (;;) {
        const size_t end = value.find('\0', at);
        if (end == std::string::npos || end - at > 255) return "a channel name does not end within 255 characters";
        if (end == at) {
            if (end + 1 != value.size()) return "its channels end before its size";
            return "";
        }
        const std::string name = value.substr(at, end - at);
        if (end + 17 > value.size()) return "the channel '" + name + "' ends past its size";
        const uint32_t pixelType = Le32(value.data() + end + 1);
        if (pixelType > 2)
            return "the channel '" + name + "' has pixel type " + std::to_string(pixelType) +
                   " (0, 1 and 2 are uint, half and float)";
        at = end + 17;
    }
}

/// Why a preview image's `value` is refused, or "": OpenEXR allocates its width x height pixels
/// (4 bytes each) before it reads them, so they must be what the value holds.
std::string BadPreview(const std::string& value) {
    if (value.size() < 8) return "the preview image has no size";
    const uint64_t width = Le32(value.data()), height = Le32(value.data() + 4);
    // (Each side at most the value's size first, so that the product cannot wrap around.)
    if (width > value.size() || height > value.size() || 8 + width * height * 4 != value.size())
        return "the preview image of " + std::to_string(width) + " x " + std::to_string(height) +
               " pixels does not fill its " + std::to_string(value.size()) + " bytes";
    return "";
}

/// Why a string vector's `value` is refused, or "": OpenEXR allocates each string's stated size
/// before it reads it, so each must lie within the value.
std::string BadStringVector(const std::string& value) {
    for (size_t at = 0; at < value.size();) {
        if (at + 4 > value.size()) return "a string's size ends past the attribute's";
        const uint64_t length = Le32(value.data() + at);
        if (length > value.size() - at - 4)
            return "a string claims " + std::to_string(length) + " bytes, but the attribute has " +
                   std::to_string(value.size() - at - 4) + " left";
        at += 4 + length;
    }
    return "";
}

/// The size of an attribute of the OpenEXR type `type`, or -1 for a type of any size. OpenEXR reads
/// a value of these types in its own size whatever the attribute says, so that a wrong size would
/// make it read the fields after it from other bytes than the ones checked here.
int FixedSize(const std::string& type) {
    static const struct {
        const char* type;
        int size;
    } kSizes[] = {
        {"box2i", 16},
        {"box2f", 16},
        {"chromaticities", 32},
        {"compression", 1},
        {"deepImageState", 1},
        {"double", 8},
        {"envmap", 1},
        {"float", 4},
        {"int", 4},
        {"keycode", 28},
        {"lineOrder", 1},
        {"m33f", 36},
        {"m33d", 72},
        {"m44f", 64},
        {"m44d", 128},
        {"rational", 8},
        {"tiledesc", 9},
        {"timecode", 8},
        {"v2i", 8},
        {"v2f", 8},
        {"v2d", 16},
        {"v3i", 12},
        {"v3f", 12},
        {"v3d", 24},
    };
    for (const auto& s : kSizes)
        if (type == s.type) return s.size;
    return -1;
}

}  // namespace

std::string OversizedExrHeader(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    unsigned char head[8] = {};
    if (!in.read(reinterpret_cast<char*>(head), 8)) return "";
    if (!(head[0] == 0x76 && head[1] == 0x2f && head[2] == 0x31 && head[3] == 0x01)) return "";
    const bool multipart = (head[5] & 0x10) != 0;
    // Names and type names: 1-31 characters, or up to 255 in a file with the long-names flag. A
    // longer one is refused rather than read: OpenEXR stops reading a name at its limit and takes
    // what follows for the next field, so that the sizes it would then read are not the ones
    // checked here (found by fuzz_texture: a name of 60 bytes hid a 2 GB string's claim).
    const size_t maxName = (head[5] & 0x04) != 0 ? 255 : 31;
    in.seekg(0, std::ios::end);
    const auto size = static_cast<uint64_t>(in.tellg());
    in.seekg(8);
    const char* const early = "the OpenEXR header ends before the end of its attributes";
    std::string tooLong;
    // A name or type: up to maxName characters and a terminating 0.
    auto word = [&](std::string* out) {
        out->clear();
        for (char c; in.get(c);) {
            if (c == '\0') return true;
            if (out->size() == maxName) {
                tooLong = "an OpenEXR attribute's name or type at byte " +
                          std::to_string(static_cast<uint64_t>(in.tellg()) - maxName - 1) + " is longer than " +
                          std::to_string(maxName) + " characters";
                return false;
            }
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
            if (!word(&name)) return tooLong.empty() ? early : tooLong;
            if (name.empty()) break;
            unsigned char bytes[4];
            if (!word(&type)) return tooLong.empty() ? early : tooLong;
            if (!in.read(reinterpret_cast<char*>(bytes), 4)) return early;
            const uint64_t length = Le32(bytes);
            const auto at = static_cast<uint64_t>(in.tellg());
            if (length > size - at)
                return "the OpenEXR attribute '" + name + "' claims " + std::to_string(length) +
                       " bytes, but the file has " + std::to_string(size - at) + " left";
            if (const int fixed = FixedSize(type); fixed >= 0 && length != static_cast<uint64_t>(fixed))
                return "the OpenEXR attribute '" + name + "' at byte " + std::to_string(at) + " has " +
                       std::to_string(length) + " bytes, where its type " + type + " has " + std::to_string(fixed);
            if (type == "chlist" || type == "preview" || type == "stringvector") {
                std::string value(length, '\0');
                in.read(value.data(), static_cast<std::streamsize>(length));
                const std::string why = type == "chlist"    ? BadChannelList(value)
                                        : type == "preview" ? BadPreview(value)
                                                            : BadStringVector(value);
                if (!why.empty())
                    return "the OpenEXR attribute '" + name + "' at byte " + std::to_string(at) + ": " + why;
            }
            in.seekg(static_cast<std::streamoff>(at + length));
        }
        if (!multipart) return "";
    }
}

}  // namespace affray::image
