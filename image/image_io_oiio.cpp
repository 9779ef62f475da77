// image/image_io_oiio.cpp: the image-file module (libaffray_image_io.so), the only code of
// affray that calls OpenImageIO. image/image_io.h says why it is a module.
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "image/exr_check.h"
#include "image/image_io.h"

namespace affray::image::io {
namespace {

/// An OIIO message on one line.
std::string OneLine(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    for (size_t p; (p = s.find('\n')) != std::string::npos;) s.replace(p, 1, "; ");
    return s.empty() ? "unknown error" : s;
}

/// Why the PNG file at `path` cannot be read whole, or "" when it can or is not a PNG. Every chunk
/// (length, type, data, CRC) must lie within the file, up to IEND. Checked before OpenImageIO
/// opens the file because Debian's OpenImageIO 2.4 leaks on a PNG that ends early:
/// PNGInput::PngReadCallback hands libpng's png_error the text of a std::string, and png_error
/// longjmps past its destructor (found by fuzz_texture; fuzz/regressions/fuzz_texture holds the
/// input). With every chunk present, libpng's reads are never short.
std::string TruncatedPng(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    unsigned char head[8] = {};
    if (!in.read(reinterpret_cast<char*>(head), 8)) return "";
    static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (!std::equal(head, head + 8, kSignature)) return "";
    in.seekg(0, std::ios::end);
    const auto size = static_cast<uint64_t>(in.tellg());
    uint64_t at = 8;
    for (;;) {
        in.seekg(static_cast<std::streamoff>(at));
        if (!in.read(reinterpret_cast<char*>(head), 8))
            return "the PNG file ends at byte " + std::to_string(size) + ", before its IEND chunk";
        const uint64_t length = uint64_t{head[0]} << 24 | uint64_t{head[1]} << 16 | uint64_t{head[2]} << 8 | head[3];
        const std::string type(reinterpret_cast<const char*>(head + 4), 4);
        const uint64_t end = at + 12 + length;
        if (end > size)
            return "the PNG chunk at byte " + std::to_string(at) + " needs " + std::to_string(end) +
                   " bytes, but the file has " + std::to_string(size);
        if (type == "IEND") return "";
        at = end;
    }
}

/// Why the GIF file at `path` is not read, or "" when it may be or is not a GIF: OpenImageIO's GIF
/// reader allocates the whole canvas of 4-byte pixels as it opens the file, in a size it computes
/// in an int, so that a 60-byte file claiming 31090 x 29440 pixels takes 3.6 GB or ends the
/// process by an uncaught length_error (both found by fuzz_texture; fuzz/regressions/fuzz_texture
/// holds the inputs). A GIF of more than kMaxGifPixels is refused before it is opened.
constexpr uint64_t kMaxGifPixels = uint64_t{1} << 26;  // 8192 x 8192, a 256 MB canvas
std::string OversizedGif(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    unsigned char head[10] = {};
    in.read(reinterpret_cast<char*>(head), sizeof head);
    if (in.gcount() < 4 || std::string_view(reinterpret_cast<const char*>(head), 4) != "GIF8") return "";
    if (in.gcount() < 10) return "the GIF file ends in its header, at byte " + std::to_string(in.gcount());
    const uint64_t width = head[6] | head[7] << 8, height = head[8] | head[9] << 8;
    if (width * height <= kMaxGifPixels) return "";
    return "the GIF canvas of " + std::to_string(width) + " x " + std::to_string(height) +
           " pixels is larger than affray reads (" + std::to_string(kMaxGifPixels) + " pixels)";
}

/// Calls `read`, turning an exception thrown inside OpenImageIO or a library it calls (a reader
/// sizing a buffer from a damaged header) into the false, nullptr or empty value of its type, with
/// the exception's text in `*thrown`.
template <class Read>
auto Guarded(std::string* thrown, Read&& read) -> decltype(read()) {
    try {
        return read();
    } catch (const std::exception& e) {
        *thrown = std::string("the image library failed: ") + e.what();
    } catch (...) {
        *thrown = "the image library failed with an unknown exception";
    }
    return {};
}

/// The OpenImageIO format that reads `path`: the one its first bytes are the signature of, else
/// the one its extension names; "" with the reason in `*why` if neither, or if affray does not
/// read that format. One reader only: OpenImageIO's own open tries every reader it has on a file
/// that its extension's reader cannot read, and Debian's RLA reader (2.4, built with assertions)
/// aborts the process on a malformed channel type. And only the formats of texture maps: the
/// readers of the others met under fuzz_texture allocated what a damaged header claimed as they
/// opened the file (DPX: 1.9 GB from a 6 KB file) or read past their buffers (BMP); the readers of
/// these ran a million inputs clean (GIF, PNG and OpenEXR after the checks above; Targa, known by
/// its extension alone, is not fuzzed). Every input is in fuzz/regressions/fuzz_texture.
std::string FormatOf(const std::string& path, std::string* why) {
    using namespace std::string_view_literals;
    static constexpr struct {
        std::string_view format, name;
        bool read;
    } kFormats[] = {
        {"tiff", "TIFF", true},      {"openexr", "OpenEXR", true},  {"png", "PNG", true},
        {"jpeg", "JPEG", true},      {"hdr", "Radiance HDR", true}, {"pnm", "PNM", true},
        {"bmp", "BMP", false},       {"gif", "GIF", true},          {"targa", "Targa", true},
        {"dds", "DDS", false},       {"psd", "Photoshop", false},   {"dpx", "DPX", false},
        {"cineon", "Cineon", false}, {"sgi", "SGI", false},         {"fits", "FITS", false},
        {"rla", "RLA", false},
    };
    static constexpr struct {
        std::string_view magic, format;
    } kSignatures[] = {
        {"\x89PNG"sv, "png"},
        {"\xff\xd8\xff"sv, "jpeg"},
        {"v/1\x01"sv, "openexr"},
        {"II*\0"sv, "tiff"},
        {"MM\0*"sv, "tiff"},
        {"II+\0"sv, "tiff"},
        {"MM\0+"sv, "tiff"},
        {"BM"sv, "bmp"},
        {"#?"sv, "hdr"},
        {"GIF8"sv, "gif"},
        {"DDS "sv, "dds"},
        {"8BPS"sv, "psd"},
        {"SDPX"sv, "dpx"},
        {"XPDS"sv, "dpx"},
        {"\x80\x2a\x5f\xd7"sv, "cineon"},
        {"\x01\xda"sv, "sgi"},
        {"SIMPLE"sv, "fits"},
    };
    const auto decide = [&](std::string_view format, const char* how) -> std::string {
        std::string name = "'" + std::string(format) + "'";
        for (const auto& f : kFormats)
            if (f.format == format) {
                if (f.read && OIIO::is_imageio_format_name(f.format)) return std::string(format);
                name = f.name;
            }
        *why = name + " by its " + how +
               ", not a format affray reads texture maps from: TIFF, OpenEXR, PNG, JPEG, Radiance HDR, PNM, "
               "GIF or Targa (convert it, e.g. with oiiotool)";
        return "";
    };
    char head[8] = {};
    std::ifstream in(path, std::ios::binary);
    in.read(head, sizeof head);
    const std::string_view bytes(head, static_cast<size_t>(in.gcount()));
    for (const auto& s : kSignatures)
        if (bytes.substr(0, s.magic.size()) == s.magic) return decide(s.format, "signature");
    if (bytes.size() >= 2 && bytes[0] == 'P' && std::string_view("123456fF").find(bytes[1]) != std::string_view::npos)
        return decide("pnm", "signature");
    const size_t slash = path.find_last_of('/'), dot = path.find_last_of('.');
    const bool hasExtension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    if (hasExtension) {
        std::string extension = path.substr(dot + 1);
        for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        for (const auto& [format, extensions] : OIIO::get_extension_map())
            if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end())
                return decide(format, "extension");
    }
    *why = "not a file of an image format affray reads (no known signature";
    *why += hasExtension ? ", nor extension)" : ")";
    return "";
}

OIIO::TypeDesc TypeOf(PixelFormat f) {
    switch (f) {
        case PixelFormat::Half: return OIIO::TypeDesc::HALF;
        case PixelFormat::UInt8: return OIIO::TypeDesc::UINT8;
        case PixelFormat::UInt16: return OIIO::TypeDesc::UINT16;
        case PixelFormat::Float: break;
    }
    return OIIO::TypeDesc::FLOAT;
}

/// Reads scanlines in the file's own pixel type (read_native_scanlines) into a scratch buffer kept
/// between reads, then converts to float: read_scanlines allocates (and frees) a buffer per call,
/// which a small texture budget turns into one large allocation per tile read (under
/// AddressSanitizer a fresh mapping each time, 80 times slower). Files with a type per channel
/// keep OpenImageIO's conversion.
class OiioReader final : public ImageReader {
  public:
    OiioReader(std::unique_ptr<OIIO::ImageInput> input, const ImageHeader& header, OIIO::TypeDesc native)
        : m_input(std::move(input)), m_header(header), m_native(native) {}
    const ImageHeader& header() const override { return m_header; }
    bool readScanlines(int y0, int y1, float* out) override {
        return Guarded(&m_thrown, [&] { return scanlines(y0, y1, out); });
    }
    bool readTiles(int x0, int x1, int y0, int y1, float* out) override {
        // (OpenImageIO's conversion here: a format's native tile read may write whole tiles past
        // the image's edge.)
        return Guarded(&m_thrown, [&] {
            return m_input->read_tiles(0, 0, m_header.x + x0, m_header.x + x1, m_header.y + y0, m_header.y + y1,
                                       m_header.z, m_header.z + 1, 0, m_header.channels, OIIO::TypeDesc::FLOAT, out);
        });
    }
    std::string error() override { return m_thrown.empty() ? OneLine(m_input->geterror()) : m_thrown; }

  private:
    bool scanlines(int y0, int y1, float* out) {
        if (m_native == OIIO::TypeDesc::UNKNOWN)
            return m_input->read_scanlines(0, 0, m_header.y + y0, m_header.y + y1, m_header.z, 0, m_header.channels,
                                           OIIO::TypeDesc::FLOAT, out);
        const auto read = [&](void* data) {
            return m_input->read_native_scanlines(0, 0, m_header.y + y0, m_header.y + y1, m_header.z, data);
        };
        if (m_native == OIIO::TypeDesc::FLOAT) return read(out);
        const size_t count = static_cast<size_t>(y1 - y0) * m_header.width * m_header.channels;
        m_scratch.resize(count * m_native.size());
        return read(m_scratch.data()) && OIIO::convert_pixel_values(m_native, m_scratch.data(), OIIO::TypeDesc::FLOAT,
                                                                    out, static_cast<int>(count));
    }

    std::unique_ptr<OIIO::ImageInput> m_input;
    ImageHeader m_header;
    OIIO::TypeDesc m_native;  ///< the file's one pixel type, or UNKNOWN for a type per channel
    std::vector<unsigned char> m_scratch;
    std::string m_thrown;  ///< what an exception inside OpenImageIO said, if one was thrown
};

class OiioImageIo final : public ImageIo {
  public:
    std::unique_ptr<ImageReader> Open(const std::string& path, std::string* error) const override {
        return Guarded(error, [&] { return open(path, error); });
    }

    bool MakeTx(const std::string& picture, const std::string& output, const std::string& wrapmodes,
                std::optional<PixelFormat> format, std::string* error) const override {
        return Guarded(error, [&] { return makeTx(picture, output, wrapmodes, format, error); });
    }

    bool Write(const std::string& path, int width, int height, int channels, const float* texels,
               const WriteLayout& layout, std::string* error) const override {
        return Guarded(error, [&] { return write(path, width, height, channels, texels, layout, error); });
    }

  private:
    /// The file at `path` opened by the one reader FormatOf picks, once that format's check above
    /// passes (each check is of a format known by its signature, which FormatOf looks at first).
    static std::unique_ptr<OIIO::ImageInput> openInput(const std::string& path, std::string* error) {
        const std::string format = FormatOf(path, error);
        if (format.empty()) return nullptr;
        const std::string why = format == "png"       ? TruncatedPng(path)
                                : format == "openexr" ? OversizedExrHeader(path)
                                : format == "gif"     ? OversizedGif(path)
                                                      : std::string();
        if (!why.empty()) {
            *error = why;
            return nullptr;
        }
        std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::create(format);
        OIIO::ImageSpec opened;
        if (!input || !input->open(path, opened)) {
            const std::string why = input ? input->geterror() : OIIO::geterror();
            *error = OneLine(why.empty() ? "the " + format + " reader cannot read it" : why);
            return nullptr;
        }
        return input;
    }

    static std::unique_ptr<ImageReader> open(const std::string& path, std::string* error) {
        std::unique_ptr<OIIO::ImageInput> input = openInput(path, error);
        if (!input) return nullptr;
        const OIIO::ImageSpec spec = input->spec(0, 0);
        ImageHeader h;
        h.width = spec.width;
        h.height = spec.height;
        h.channels = spec.nchannels;
        h.x = spec.x;
        h.y = spec.y;
        h.z = spec.z;
        if (spec.tile_width > 0 && spec.tile_height > 0) {
            h.tileWidth = spec.tile_width;
            h.tileHeight = spec.tile_height;
        }
        h.wrapmodes = spec.get_string_attribute("wrapmodes");
        while (input->seek_subimage(0, h.mipLevels)) ++h.mipLevels;
        if (!input->seek_subimage(0, 0)) {
            *error = OneLine(input->geterror());
            return nullptr;
        }
        const OIIO::TypeDesc native = spec.channelformats.empty() ? spec.format : OIIO::TypeDesc::UNKNOWN;
        return std::make_unique<OiioReader>(std::move(input), h, native);
    }

    static bool makeTx(const std::string& picture, const std::string& output, const std::string& wrapmodes,
                       std::optional<PixelFormat> format, std::string* error) {
        OIIO::ImageSpec config;
        if (format) config.format = TypeOf(*format);
        config.attribute("wrapmodes", wrapmodes);
        // Always a TIFF, whatever the name: prman's txmake names its files .tex or .tx, and the
        // scenes written for it name the made file so (OIIO picks a writer by extension).
        config.attribute("maketx:fileformatname", "tiff");
        // The picture is read here, by the one reader openInput picks after its checks, not by
        // make_texture's own open (which would try every reader on a damaged file).
        std::unique_ptr<OIIO::ImageInput> input = openInput(picture, error);
        if (!input) return false;
        OIIO::ImageBuf image(input->spec(0, 0));
        if (!input->read_image(0, 0, 0, image.nchannels(), image.spec().format, image.localpixels())) {
            *error = OneLine(input->geterror());
            return false;
        }
        std::ostringstream messages;
        if (OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, image, output, config, &messages))
            return true;
        *error = OneLine(messages.str());
        return false;
    }

    static bool write(const std::string& path, int width, int height, int channels, const float* texels,
                      const WriteLayout& layout, std::string* error) {
        auto fail = [&](const std::string& why) {
            *error = "cannot write '" + path + "': " + OneLine(why);
            return false;
        };
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
        if (!out) return fail(OIIO::geterror());
        OIIO::ImageSpec spec(width, height, channels, TypeOf(layout.format));
        if (layout.tile) spec.tile_width = spec.tile_height = layout.tile;
        if (!layout.wrapmodes.empty()) spec.attribute("wrapmodes", layout.wrapmodes);
        // OIIO's TIFF writer takes no MIP levels as such: like maketx, it writes them as subimages
        // of a "Plain Texture", which its reader reads as MIP levels.
        const bool asMipLevels = out->supports("mipmap");
        if (layout.mipmap && !asMipLevels && !out->supports("multiimage"))
            return fail("the format stores no MIP levels");
        if (layout.mipmap && !asMipLevels) spec.attribute("textureformat", "Plain Texture");
        if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, texels)) return fail(out->geterror());
        if (layout.mipmap) {
            std::vector<float> level(texels, texels + static_cast<size_t>(width) * height * channels);
            int w = width, h = height;
            while (w > 1 || h > 1) {
                const int nw = std::max(1, w / 2), nh = std::max(1, h / 2);
                std::vector<float> next(static_cast<size_t>(nw) * nh * channels);
                for (int y = 0; y < nh; ++y)
                    for (int x = 0; x < nw; ++x)
                        for (int c = 0; c < channels; ++c) {
                            double sum = 0;
                            for (int dy = 0; dy < 2; ++dy)
                                for (int dx = 0; dx < 2; ++dx)
                                    sum += level[(static_cast<size_t>(std::min(2 * y + dy, h - 1)) * w +
                                                  std::min(2 * x + dx, w - 1)) *
                                                     channels +
                                                 c];
                            next[(static_cast<size_t>(y) * nw + x) * channels + c] = static_cast<float>(sum / 4);
                        }
                OIIO::ImageSpec s(nw, nh, channels, TypeOf(layout.format));
                if (layout.tile) s.tile_width = s.tile_height = layout.tile;
                if (!asMipLevels) s.attribute("textureformat", "Plain Texture");
                if (!out->open(path, s,
                               asMipLevels ? OIIO::ImageOutput::AppendMIPLevel : OIIO::ImageOutput::AppendSubimage) ||
                    !out->write_image(OIIO::TypeDesc::FLOAT, next.data()))
                    return fail(out->geterror());
                level = std::move(next);
                w = nw;
                h = nh;
            }
        }
        if (!out->close()) return fail(out->geterror());
        return true;
    }
};

}  // namespace
}  // namespace affray::image::io

extern "C" __attribute__((visibility("default"))) const affray::image::io::ImageIo* affray_image_io(int abi) {
    static const affray::image::io::OiioImageIo io;
    return abi == affray::image::io::kAbi ? &io : nullptr;
}
