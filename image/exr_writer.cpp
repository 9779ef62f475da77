// image/exr_writer.cpp: OpenEXR output and input (format and atomicity rules in exr_writer.h).
#include "image/exr_writer.h"

#include "diag/limits.h"

#include "image/atomic_file.h"
#include "image/exr_check.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <algorithm>
#include <cstdint>
#include <exception>
#include <memory>
#include <set>
#include <stdexcept>

namespace affray::image {
namespace {

constexpr const char* kRgbaNames[4] = {"R", "G", "B", "A"};
// Refuse images larger than the image-pixels limit: a corrupt header must not make us allocate
// without bound.
int64_t MaxPixels() { return diag::LimitValue(diag::Limit::ImagePixels); }

// Checks sizes and channel names before any file is touched; returns "" if the image is valid.
std::string ValidateImage(const ImageBuffer& image) {
    if (image.width <= 0 || image.height <= 0)
        return "image size " + std::to_string(image.width) + "x" + std::to_string(image.height) + " is empty";
    int64_t pixels = int64_t(image.width) * image.height;
    if (pixels > MaxPixels())
        return "image of " + std::to_string(pixels) + " pixels is too large " +
               diag::LimitNote(diag::Limit::ImagePixels);
    if (image.rgba.size() != size_t(pixels) * 4)
        return "RGBA buffer holds " + std::to_string(image.rgba.size()) + " floats, expected " +
               std::to_string(pixels * 4);
    std::set<std::string> names(std::begin(kRgbaNames), std::end(kRgbaNames));
    for (const auto& [name, values] : image.extraChannels) {
        if (name.empty()) return "extra channel with an empty name";
        if (!names.insert(name).second) return "channel '" + name + "' is given twice";
        if (values.size() != size_t(pixels))
            return "channel '" + name + "' holds " + std::to_string(values.size()) + " values, expected " +
                   std::to_string(pixels);
    }
    return "";
}

/// An OpenEXR output stream into memory: the file is encoded whole, then written by
/// WriteFileAtomically, whose error checks then cover every byte.
class MemoryStream : public Imf::OStream {
  public:
    MemoryStream(const std::string& name) : Imf::OStream(name.c_str()) {}
    void write(const char c[], int n) override {
        if (m_pos + size_t(n) > m_bytes.size()) m_bytes.resize(m_pos + size_t(n));
        std::copy(c, c + n, m_bytes.begin() + static_cast<std::ptrdiff_t>(m_pos));
        m_pos += size_t(n);
    }
    uint64_t tellp() override { return m_pos; }
    void seekp(uint64_t pos) override { m_pos = pos; }
    const std::string& bytes() const { return m_bytes; }

  private:
    std::string m_bytes;
    size_t m_pos = 0;
};

// Encodes the image as an OpenEXR file into `out`. Throws what OpenEXR throws.
void EncodeExr(const ImageBuffer& image, MemoryStream& out) {
    Imf::Header header(image.width, image.height);
    for (const char* name : kRgbaNames) header.channels().insert(name, Imf::Channel(Imf::HALF));
    for (const auto& channel : image.extraChannels) header.channels().insert(channel.first, Imf::Channel(Imf::FLOAT));
    for (const auto& [name, value] : image.attributes) header.insert(name, Imf::StringAttribute(value));

    // RGBA goes to disk as half; convert once into an interleaved buffer.
    std::vector<Imath::half> rgba(image.rgba.size());
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = Imath::half(image.rgba[i]);

    Imf::FrameBuffer frameBuffer;
    const size_t halfPixel = 4 * sizeof(Imath::half);
    for (int c = 0; c < 4; ++c)
        frameBuffer.insert(kRgbaNames[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(rgba.data() + c), halfPixel,
                                                     halfPixel * image.width));
    for (const auto& [name, values] : image.extraChannels)
        frameBuffer.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(values.data())),
                                            sizeof(float), sizeof(float) * image.width));

    Imf::OutputFile file(out, header);
    file.setFrameBuffer(frameBuffer);
    file.writePixels(image.height);
}  // the file's offset table is written here, when `file` closes

}  // namespace

std::string ToString(const ImageBuffer& image) {
    std::string text = std::to_string(image.width) + "x" + std::to_string(image.height) + " RGBA";
    for (const auto& channel : image.extraChannels) text += " + " + channel.first;
    return text;
}

bool WriteExr(const std::string& path, const ImageBuffer& image, diag::Report* report) {
    auto fail = [&](const std::string& reason) {
        if (report) report->error({path}, "cannot write file: " + reason);
        return false;
    };
    if (path.empty()) return fail("empty file name");
    if (std::string reason = ValidateImage(image); !reason.empty()) return fail(reason);

    MemoryStream encoded(path);
    try {
        EncodeExr(image, encoded);
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    std::string reason;
    if (!WriteFileAtomically(path, encoded.bytes(), &reason)) return fail(reason);
    return true;
}

namespace {

/// The file at `path` opened for reading, once its headers pass OversizedExrHeader; throws why not.
std::unique_ptr<Imf::InputFile> OpenExr(const std::string& path) {
    if (const std::string why = OversizedExrHeader(path); !why.empty()) throw std::runtime_error(why);
    return std::make_unique<Imf::InputFile>(path.c_str());
}

/// Size and attributes of an open file's header, and its extra channels' names (no values).
ImageBuffer HeaderOf(const Imf::InputFile& file) {
    const Imath::Box2i dataWindow = file.header().dataWindow();
    int64_t width = int64_t(dataWindow.max.x) - dataWindow.min.x + 1;
    int64_t height = int64_t(dataWindow.max.y) - dataWindow.min.y + 1;
    if (width <= 0 || height <= 0 || width * height > MaxPixels())
        throw std::runtime_error("unsupported data window " + std::to_string(width) + "x" + std::to_string(height) +
                                 (width > 0 && height > 0 ? " " + diag::LimitNote(diag::Limit::ImagePixels) : ""));
    ImageBuffer image;
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    for (auto it = file.header().begin(); it != file.header().end(); ++it)
        if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
            image.attributes[it.name()] = text->value();
    const Imf::ChannelList& channels = file.header().channels();
    for (auto it = channels.begin(); it != channels.end(); ++it) {
        std::string name = it.name();
        if (name == "R" || name == "G" || name == "B" || name == "A") continue;
        if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
            throw std::runtime_error("subsampled channel '" + name + "' is not supported");
        image.extraChannels.emplace_back(name, std::vector<float>());
    }
    return image;
}

}  // namespace

bool ReadExrHeader(const std::string& path, ImageBuffer* out, diag::Report* report) {
    try {
        *out = HeaderOf(*OpenExr(path));
        return true;
    } catch (const std::exception& e) {
        if (report) report->error({path}, std::string("cannot read image: ") + e.what());
        return false;
    }
}

bool ReadExrRgba(const std::string& path, ImageBuffer* out, diag::Report* report,
                 std::optional<std::array<int, 2>> rows) {
    try {
        const std::unique_ptr<Imf::InputFile> opened = OpenExr(path);
        Imf::InputFile& file = *opened;
        const Imath::Box2i dataWindow = file.header().dataWindow();
        ImageBuffer image = HeaderOf(file);
        // The rows read, as a box in the file's coordinates: all, or the band asked for.
        Imath::Box2i band = dataWindow;
        if (rows) {
            if ((*rows)[0] < 0 || (*rows)[1] > image.height || (*rows)[0] >= (*rows)[1])
                throw std::runtime_error("rows " + std::to_string((*rows)[0]) + " to " + std::to_string((*rows)[1]) +
                                         " are not in the image");
            band.min.y = dataWindow.min.y + (*rows)[0];
            band.max.y = dataWindow.min.y + (*rows)[1] - 1;
            image.height = (*rows)[1] - (*rows)[0];
        }
        const size_t pixels = size_t(image.width) * size_t(image.height);
        image.rgba.assign(pixels * 4, 0.0f);
        Imf::FrameBuffer frameBuffer;
        for (int c = 0; c < 4; ++c)
            frameBuffer.insert(kRgbaNames[c],
                               Imf::Slice::Make(Imf::FLOAT, image.rgba.data() + c, band, 4 * sizeof(float),
                                                4 * sizeof(float) * image.width, 1, 1, c == 3 ? 1.0 : 0.0));
        for (auto& [name, values] : image.extraChannels) {
            values.assign(pixels, 0.0f);
            frameBuffer.insert(
                name, Imf::Slice::Make(Imf::FLOAT, values.data(), band, sizeof(float), sizeof(float) * image.width));
        }
        file.setFrameBuffer(frameBuffer);
        file.readPixels(band.min.y, band.max.y);
        *out = std::move(image);
        return true;
    } catch (const std::exception& e) {
        if (report) report->error({path}, std::string("cannot read image: ") + e.what());
        return false;
    }
}

}  // namespace affray::image
