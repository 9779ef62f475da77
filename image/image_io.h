// image/image_io.h: image files through OpenImageIO, which lives in a module of its own
// (libaffray_image_io.so) loaded the first time an image is read or written.
//
// Why a module: OpenImageIO brings some 260 shared libraries (codecs, OpenCV, FFmpeg...), and
// linking it made every process of affray pay about 0.3 s of dynamic loading at start-up, scenes
// without textures and each test of the suite included. Only a process that touches an image file
// now pays it. No binary links OpenImageIO; everything here crosses the module boundary through
// the abstract classes below (same compiler and C++ library on both sides: the module is built
// with affray and found beside it).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace affray::image::io {

/// What a reader knows of subimage 0, MIP level 0 of a file.
struct ImageHeader {
    int width = 0, height = 0, channels = 0;
    int x = 0, y = 0, z = 0;            // the data window's origin
    int tileWidth = 0, tileHeight = 0;  // 0: a scanline file
    int mipLevels = 1;                  // levels of subimage 0
    std::string wrapmodes;              // the file's "wrapmodes" attribute, "" if none
};

/// An open image file: reads level 0 of subimage 0 as float, all channels interleaved. Not
/// thread-safe: one read at a time.
class ImageReader {
  public:
    virtual ~ImageReader() = default;
    virtual const ImageHeader& header() const = 0;
    /// Rows [y0, y1) of a scanline file, whole, (y relative to the data window).
    virtual bool readScanlines(int y0, int y1, float* out) = 0;
    /// The file tiles covering [x0, x1) x [y0, y1) of a tiled file; the rectangle is aligned to
    /// tiles (or the image's edge).
    virtual bool readTiles(int x0, int x1, int y0, int y1, float* out) = 0;
    /// Why the last call failed, on one line.
    virtual std::string error() = 0;
};

/// How an image is stored by Write.
enum class PixelFormat { Float, Half, UInt8, UInt16 };
struct WriteLayout {
    PixelFormat format = PixelFormat::Float;
    int tile = 0;           // tile size, 0 for scanlines
    bool mipmap = false;    // also write the coarser levels, each a box-filtered half of the one before
    std::string wrapmodes;  // the "wrapmodes" attribute, "" for none
};

/// The operations of the module.
class ImageIo {
  public:
    virtual ~ImageIo() = default;
    /// Opens a file; null with `*error` (one line, OpenImageIO's reason) if it cannot be read.
    virtual std::unique_ptr<ImageReader> Open(const std::string& path, std::string* error) const = 0;
    /// OpenImageIO's maketx: `picture` to a tiled, mip-mapped texture with the given wrapmodes
    /// attribute and texel format (the picture's if none). False with `*error` (one line).
    virtual bool MakeTx(const std::string& picture, const std::string& output, const std::string& wrapmodes,
                        std::optional<PixelFormat> format, std::string* error) const = 0;
    /// Writes width x height x channels float texels (converted to the layout's format).
    virtual bool Write(const std::string& path, int width, int height, int channels, const float* texels,
                       const WriteLayout& layout, std::string* error) const = 0;
};

/// The module's entry point, a C symbol so that dlsym finds it by name; `abi` is kAbi.
inline constexpr int kAbi = 1;
using EntryPoint = const ImageIo* (*)(int abi);
inline constexpr const char* kEntryName = "affray_image_io";
inline constexpr const char* kModuleFile = "libaffray_image_io.so";

/// The module, loaded on first use (thread-safe) from, in order: $AFFRAY_IMAGE_IO (a path), the
/// directory of the running executable, the path it was built at. Null with `*error` saying
/// where it looked if none loads; the answer is then the same for the life of the process.
const ImageIo* Get(std::string* error);

/// Whether the module has been loaded by this process (the start-up test checks that a render
/// without textures never loads it).
bool Loaded();

}  // namespace affray::image::io
