// tests/image/exr_writer_test.cpp: OpenEXR output (image/exr_writer.*): round trips, channel
// types, and clean failure without leftover temporary files.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "image/exr_writer.h"
#include "tests/test_util.h"

using namespace affray::image;
namespace fs = std::filesystem;

namespace {

// A fresh empty directory, removed with everything in it at scope exit.
struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() /
               ("affray_exr_test_" + std::to_string(::getpid()) + "_" + std::to_string(std::random_device{}()));
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    std::vector<std::string> Entries() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(path)) names.push_back(entry.path().filename());
        return names;
    }
};

ImageBuffer TestImage(int width, int height) {
    ImageBuffer image;
    image.width = width;
    image.height = height;
    image.rgba.resize(size_t(width) * height * 4);
    std::vector<float> z(size_t(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            size_t i = size_t(y) * width + x;
            image.rgba[4 * i + 0] = x / float(width);
            image.rgba[4 * i + 1] = y / float(height);
            image.rgba[4 * i + 2] = 0.25f + 100.0f * x * y;  // beyond [0,1] on purpose
            image.rgba[4 * i + 3] = (x + y) % 2 ? 1.0f : 0.5f;
            z[i] = 1.0f + 0.001f * x + 1000.0f * y;  // needs float precision
        }
    image.extraChannels.emplace_back("Z", std::move(z));
    return image;
}

}  // namespace

TEST_CASE("EXR round trip keeps RGBA to half precision and Z exactly", "[image]") {
    TempDir dir;
    std::string path = (dir.path / "image.exr").string();
    ImageBuffer image = TestImage(7, 5);
    affray::diag::Report error;
    REQUIRE(WriteExr(path, image, &error));
    CHECK(dir.Entries() == std::vector<std::string>{"image.exr"});  // no temporary left

    ImageBuffer back;
    INFO(error);
    REQUIRE(ReadExrRgba(path, &back, &error));
    REQUIRE(back.width == 7);
    REQUIRE(back.height == 5);
    REQUIRE(back.rgba.size() == image.rgba.size());
    for (size_t i = 0; i < image.rgba.size(); ++i) {
        INFO("value " << i);
        // Half has an 11-bit significand: relative error at most 2^-11.
        CHECK(std::fabs(back.rgba[i] - image.rgba[i]) <= std::fabs(image.rgba[i]) / 2048.0f + 1e-7f);
    }
    REQUIRE(back.extraChannels.size() == 1);
    CHECK(back.extraChannels[0].first == "Z");
    CHECK(back.extraChannels[0].second == image.extraChannels[0].second);
    CHECK(ToString(back) == "7x5 RGBA + Z");
}

TEST_CASE("EXR channels are RGBA half and extra channels float", "[image]") {
    TempDir dir;
    std::string path = (dir.path / "channels.exr").string();
    ImageBuffer image = TestImage(4, 3);
    affray::diag::Report error;
    REQUIRE(WriteExr(path, image, &error));

    Imf::InputFile file(path.c_str());
    const Imf::ChannelList& channels = file.header().channels();
    for (const char* name : {"R", "G", "B", "A"}) {
        const Imf::Channel* channel = channels.findChannel(name);
        REQUIRE(channel);
        CHECK(channel->type == Imf::HALF);
    }
    const Imf::Channel* z = channels.findChannel("Z");
    REQUIRE(z);
    CHECK(z->type == Imf::FLOAT);

    // Read Z straight through OpenEXR: row 0 is the top row of the buffer.
    const Imath::Box2i window = file.header().dataWindow();
    CHECK(window.min == Imath::V2i(0, 0));
    CHECK(window.max == Imath::V2i(3, 2));
    std::vector<float> values(12);
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert(
        "Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float), 4 * sizeof(float)));
    file.setFrameBuffer(frameBuffer);
    file.readPixels(0, 2);
    CHECK(values == image.extraChannels[0].second);
    CHECK(values[4 * 2 + 3] == 1.0f + 0.003f + 2000.0f);
}

TEST_CASE("EXR writes replace an existing file", "[image]") {
    TempDir dir;
    std::string path = (dir.path / "again.exr").string();
    affray::diag::Report error;
    REQUIRE(WriteExr(path, TestImage(8, 8), &error));
    ImageBuffer second = TestImage(3, 2);
    second.extraChannels.clear();
    REQUIRE(WriteExr(path, second, &error));
    ImageBuffer back;
    REQUIRE(ReadExrRgba(path, &back, &error));
    CHECK(back.width == 3);
    CHECK(back.extraChannels.empty());
    CHECK(dir.Entries() == std::vector<std::string>{"again.exr"});
}

TEST_CASE("EXR write failures are clean", "[image]") {
    TempDir dir;
    affray::diag::Report error;

    SECTION("missing directory") {
        std::string path = (dir.path / "missing" / "out.exr").string();
        CHECK_FALSE(WriteExr(path, TestImage(2, 2), &error));
        CHECK(affray::test::LastMessage(error) ==
              path + ": error: cannot write file: directory '" + (dir.path / "missing").string() + "' does not exist");
        CHECK(dir.Entries().empty());
    }
    SECTION("target is a directory: the temporary file is written, then removed") {
        fs::create_directory(dir.path / "sub");
        std::string path = (dir.path / "sub").string();
        CHECK_FALSE(WriteExr(path, TestImage(2, 2), &error));
        CHECK(affray::test::LastMessage(error).rfind(path + ": error: cannot write file: ", 0) == 0);
        CHECK(dir.Entries() == std::vector<std::string>{"sub"});
    }
    SECTION("malformed images touch nothing") {
        std::string path = (dir.path / "bad.exr").string();
        ImageBuffer empty;
        CHECK_FALSE(WriteExr(path, empty, &error));
        CHECK(affray::test::LastMessage(error) == path + ": error: cannot write file: image size 0x0 is empty");
        ImageBuffer shortRgba = TestImage(2, 2);
        shortRgba.rgba.pop_back();
        CHECK_FALSE(WriteExr(path, shortRgba, &error));
        CHECK(affray::test::LastMessage(error) ==
              path + ": error: cannot write file: RGBA buffer holds 15 floats, expected 16");
        ImageBuffer duplicate = TestImage(2, 2);
        duplicate.extraChannels.emplace_back("A", std::vector<float>(4));
        CHECK_FALSE(WriteExr(path, duplicate, &error));
        CHECK(affray::test::LastMessage(error) == path + ": error: cannot write file: channel 'A' is given twice");
        CHECK(dir.Entries().empty());
    }
    SECTION("reading a missing or corrupt file") {
        ImageBuffer back;
        CHECK_FALSE(ReadExrRgba((dir.path / "none.exr").string(), &back, &error));
        CHECK(affray::test::LastMessage(error).rfind((dir.path / "none.exr").string() + ": error: cannot read image: ",
                                                     0) == 0);
        std::string junk = (dir.path / "junk.exr").string();
        FILE* f = std::fopen(junk.c_str(), "w");
        REQUIRE(f);
        std::fputs("not an exr file at all", f);
        std::fclose(f);
        CHECK_FALSE(ReadExrRgba(junk, &back, &error));
        CHECK(affray::test::LastMessage(error).rfind(junk + ": error: cannot read image: ", 0) == 0);
    }
}

TEST_CASE("EXR string attributes round trip, and a header alone or a band of rows can be read", "[image]") {
    TempDir dir;
    const std::string path = (dir.path / "band.exr").string();
    ImageBuffer image{5, 4, std::vector<float>(5 * 4 * 4), {{"Z", std::vector<float>(5 * 4)}}, {}};
    for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = float(i % 97) * 0.25f;
    for (size_t i = 0; i < 20; ++i) image.extraChannels[0].second[i] = float(i) + 0.5f;
    image.attributes["affray:pixels"] = "0,5,0,4";
    REQUIRE(WriteExr(path, image, nullptr));

    ImageBuffer header;
    REQUIRE(ReadExrHeader(path, &header, nullptr));
    CHECK((header.width == 5 && header.height == 4));
    CHECK(header.rgba.empty());
    REQUIRE(header.extraChannels.size() == 1);
    CHECK(header.extraChannels[0].first == "Z");
    CHECK(header.attributes.at("affray:pixels") == "0,5,0,4");

    // Rows 1 and 2: a 5 x 2 image holding exactly those rows.
    ImageBuffer band;
    REQUIRE(ReadExrRgba(path, &band, nullptr, std::array<int, 2>{1, 3}));
    CHECK((band.width == 5 && band.height == 2));
    CHECK(std::equal(band.rgba.begin(), band.rgba.end(), image.rgba.begin() + 5 * 4));
    CHECK(std::equal(band.extraChannels[0].second.begin(), band.extraChannels[0].second.end(),
                     image.extraChannels[0].second.begin() + 5));
    affray::diag::Report report;
    CHECK_FALSE(ReadExrRgba(path, &band, &report, std::array<int, 2>{3, 5}));
    CHECK(affray::test::LastMessage(report).find("rows 3 to 5 are not in the image") != std::string::npos);
}

TEST_CASE("EXR files whose attributes claim more bytes than the file holds are refused before OpenEXR reads them",
          "[image]") {
    // OpenEXR 3.1 would allocate the claim first (image/exr_check.h).
    TempDir dir;
    const std::string path = (dir.path / "claims.exr").string();
    ImageBuffer image = TestImage(3, 2);
    image.attributes["affray:pixels"] = "0,3,0,2";
    REQUIRE(WriteExr(path, image, nullptr));
    std::string bytes = affray::test::ReadText(path);
    // The attribute "affray:pixels", then its type "string", then its size: claim 1 GiB.
    const size_t name = bytes.find(std::string("affray:pixels\0string\0", 21));
    REQUIRE(name != std::string::npos);
    const size_t size = name + 21;
    bytes.replace(size, 4, std::string("\x00\x00\x00\x40", 4));
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    const std::string expected = "the OpenEXR attribute 'affray:pixels' claims 1073741824 bytes, but the file has " +
                                 std::to_string(bytes.size() - size - 4) + " left";
    ImageBuffer read;
    affray::diag::Report report;
    CHECK_FALSE(ReadExrHeader(path, &read, &report));
    CHECK(affray::test::LastMessage(report) == path + ": error: cannot read image: " + expected);
    CHECK_FALSE(ReadExrRgba(path, &read, &report));
    CHECK(affray::test::LastMessage(report) == path + ": error: cannot read image: " + expected);
}
