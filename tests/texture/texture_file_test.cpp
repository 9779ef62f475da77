// tests/texture/texture_file_test.cpp: maps read from files (texture/texture_file.cpp): every
// format's texels equal OpenImageIO's own float reading (EXR, PNG, JPEG, scanline TIFF, a tiled
// and MIP-mapped TIFF as maketx writes), the wrap modes and non-finite texels of a file, the map
// cache (same file, same map; a rewritten file, a new one; a missing file, null and a message),
// and the tile cache under a tiny budget, from one thread and from several.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <thread>
#include <tuple>

#include "tests/test_random.h"
#include "tests/test_util.h"
#include "tests/texture/texture_test_util.h"
#include "texture/texture.h"

using namespace affray::texture;
using affray::test::Rng;
using namespace affray::test::tex;

namespace {

/// Opens `path` and checks its size, channels and every texel against OIIO's float reading, and
/// its pyramid against that of a map from the same pixels.
std::shared_ptr<const TextureMap> OpenAndCompare(const std::string& path) {
    std::string error;
    auto map = Open(path, &error);
    INFO(error);
    REQUIRE(map);
    int w = 0, h = 0, ch = 0;
    const std::vector<float> ref = ReadImage(path, &w, &h, &ch);
    REQUIRE(map->width() == w);
    REQUIRE(map->height() == h);
    REQUIRE(map->channels() == ch);
    int64_t mismatches = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < ch; ++c)
                if (map->Texel(x, y, c) != ref[(static_cast<size_t>(y) * w + x) * ch + c]) ++mismatches;
    CHECK(mismatches == 0);
    auto pixels = TextureMap::FromPixels(w, h, ch, ref);
    Rng rng(16100);
    for (int i = 0; i < 200; ++i) {
        const int64_t x0 = rng.integer(-w, 2 * w), y0 = rng.integer(-h, 2 * h);
        const int64_t x1 = x0 + rng.integer(0, 2 * w), y1 = y0 + rng.integer(0, 2 * h);
        const int c = rng.integer(0, ch - 1);
        const Wrap sw = RandomWrap(rng), tw = RandomWrap(rng);
        const Range a = map->RangeOfTexels(x0, x1, y0, y1, c, sw, tw);
        const Range b = pixels->RangeOfTexels(x0, x1, y0, y1, c, sw, tw);
        CHECK((a.lo == b.lo && a.hi == b.hi));
    }
    return map;
}

std::vector<float> Gradient(int w, int h, int ch, Rng& rng) {
    std::vector<float> t(static_cast<size_t>(w) * h * ch);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < ch; ++c)
                t[(static_cast<size_t>(y) * w + x) * ch + c] =
                    static_cast<float>(std::clamp(0.5 * x / w + 0.3 * y / h + 0.2 * rng.uniform(0, 1), 0.0, 1.0));
    return t;
}

}  // namespace

TEST_CASE("texture file: every format reads as OpenImageIO reads it", "[texture]") {
    ScratchDir dir;
    Rng rng(16101);
    SECTION("EXR, float, one and three channels") {
        for (int ch : {1, 3}) {
            const std::string path = dir.path("f" + std::to_string(ch) + ".exr");
            WriteImage(path, 70, 45, ch, RandomTexels(rng, size_t{70} * 45 * ch));
            auto map = OpenAndCompare(path);
            CHECK(map->name() == path);
            CHECK(map->swrap() == Wrap::Periodic);
            CHECK(map->nonFiniteTexels() == 0);
        }
    }
    SECTION("PNG, 8 bits") {
        const std::string path = dir.path("a.png");
        WriteImage(path, 33, 20, 3, Gradient(33, 20, 3, rng), ImageLayout(PixelFormat::UInt8));
        auto map = OpenAndCompare(path);
        CHECK(map->Texel(0, 0, 0) * 255.0f == Approx(std::round(map->Texel(0, 0, 0) * 255.0f)));
    }
    SECTION("JPEG") {
        const std::string path = dir.path("a.jpg");
        WriteImage(path, 40, 30, 3, Gradient(40, 30, 3, rng), ImageLayout(PixelFormat::UInt8));
        OpenAndCompare(path);
    }
    SECTION("TIFF, scanlines, 16 bits, with wrap modes") {
        const std::string path = dir.path("a.tif");
        ImageLayout layout(PixelFormat::UInt16);
        layout.wrapmodes = "clamp,black";
        WriteImage(path, 130, 70, 2, Gradient(130, 70, 2, rng), layout);
        auto map = OpenAndCompare(path);
        CHECK(map->swrap() == Wrap::Clamp);
        CHECK(map->twrap() == Wrap::Black);
    }
    SECTION("TIFF, tiled and MIP-mapped (maketx's .tx), level 0 read") {
        const std::string path = dir.path("a.tx");
        ImageLayout layout;
        layout.format = PixelFormat::Float;
        layout.tile = 64;
        layout.mipmap = true;
        layout.wrapmodes = "black";
        const int w = 150, h = 100;
        WriteImage(path, w, h, 1, RandomTexels(rng, static_cast<size_t>(w) * h), layout);
        const affray::image::io::ImageHeader header = ReadHeader(path);
        CHECK(header.tileWidth == 64);
        CHECK(header.mipLevels > 1);
        auto map = OpenAndCompare(path);
        CHECK(map->swrap() == Wrap::Black);
        CHECK(map->twrap() == Wrap::Black);
    }
    SECTION("EXR, tiled 32, with non-finite texels") {
        const std::string path = dir.path("nan.exr");
        std::vector<float> t = RandomTexels(rng, size_t{100} * 90);
        t[5] = std::numeric_limits<float>::quiet_NaN();
        t[777] = std::numeric_limits<float>::infinity();
        t[8999] = -std::numeric_limits<float>::infinity();
        ImageLayout layout;
        layout.tile = 32;
        WriteImage(path, 100, 90, 1, t, layout);
        std::string error;
        auto map = Open(path, &error);
        REQUIRE(map);
        CHECK(map->nonFiniteTexels() == 3);
        CHECK(map->Texel(5, 0, 0) == 0.0f);
        CHECK(map->Texel(77, 7, 0) == 0.0f);
        CHECK(map->Texel(99, 89, 0) == 0.0f);
        CHECK(map->Texel(6, 0, 0) == t[6]);
        const Range r = map->RangeOfTexels(0, 99, 0, 89, 0, Wrap::Clamp, Wrap::Clamp);
        CHECK((std::isfinite(r.lo) && std::isfinite(r.hi)));
    }
}

TEST_CASE("texture file: the map cache, rewritten files, missing and broken files", "[texture]") {
    ScratchDir dir;
    Rng rng(16102);
    const std::string path = dir.path("c.exr");
    WriteImage(path, 16, 16, 1, std::vector<float>(256, 0.5f));
    std::string error;
    auto a = Open(path, &error);
    REQUIRE(a);
    CHECK(Open(path, &error) == a);
    CHECK(a->Texel(3, 3, 0) == 0.5f);

    // Rewritten, with a modification time surely different: a new map of the new texels.
    const auto before = std::filesystem::last_write_time(path);
    WriteImage(path, 16, 16, 1, std::vector<float>(256, 0.75f));
    std::filesystem::last_write_time(path, before + std::chrono::seconds(10));
    auto b = Open(path, &error);
    REQUIRE(b);
    CHECK(b != a);
    CHECK(b->Texel(3, 3, 0) == 0.75f);
    CHECK(a->Texel(3, 3, 0) == 0.5f);  // the old map stays whole for those still holding it
    CHECK(Open(path, &error) == b);

    // A file rewritten under an open map before its tiles were read: the texels read then stay
    // within the pyramid of the first reading, so the bounds still hold.
    {
        const std::string changing = dir.path("changing.exr");
        ImageLayout layout;
        layout.tile = 16;
        WriteImage(changing, 64, 64, 1, RandomTexels(rng, size_t{64} * 64), layout);
        auto before = Open(changing, &error);
        REQUIRE(before);
        WriteImage(changing, 64, 64, 1, std::vector<float>(size_t{64} * 64, 100.0f), layout);
        const Range all = before->RangeOfTexels(0, 63, 0, 63, 0, Wrap::Clamp, Wrap::Clamp);
        int outside = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const float v = before->Texel(x, y, 0);
                if (v < all.lo || v > all.hi) ++outside;
            }
        CHECK(outside == 0);
        CHECK(all.hi <= 2.0);
    }

    // Threads opening one file at once share one reading of it.
    const std::string shared = dir.path("shared.exr");
    WriteImage(shared, 40, 40, 2, RandomTexels(rng, size_t{40} * 40 * 2));
    std::vector<std::shared_ptr<const TextureMap>> opened(3);
    std::vector<std::thread> threads;
    threads.reserve(3);
    for (int k = 0; k < 3; ++k)
        threads.emplace_back([&, k] {
            std::string e;
            opened[k] = Open(shared, &e);
        });
    for (std::thread& t : threads) t.join();
    REQUIRE(opened[0]);
    CHECK(opened[1] == opened[0]);
    CHECK(opened[2] == opened[0]);

    const std::string missing = dir.path("missing.exr");
    error.clear();
    CHECK_FALSE(Open(missing, &error));
    CHECK(error.find("cannot read texture '" + missing + "'") == 0);
    CHECK(error.find('\n') == std::string::npos);

    const std::string text = dir.path("text.exr");
    std::ofstream(text) << "not an image\n";
    error.clear();
    CHECK_FALSE(Open(text, &error));
    CHECK(error.find(text) != std::string::npos);

    // One reader per file, chosen by its signature, else its extension: never OpenImageIO's
    // try-every-reader, whose RLA reader aborts the process on a damaged file
    // (fuzz/regressions/fuzz_texture/rla_channel_type_oiio_assert); RLA is not read at all.
    for (const char* name : {"image.unknown", "image"}) {
        const std::string other = dir.path(name);
        std::ofstream(other) << "not an image\n";
        error.clear();
        CHECK_FALSE(Open(other, &error));
        CHECK(error.find("not a file of an image format affray reads") != std::string::npos);
    }
    // The formats read, each as OpenImageIO writes it (Targa known by its extension alone).
    for (const char* name : {"map.tif", "map.exr", "map.png", "map.jpg", "map.hdr", "map.ppm", "map.gif", "map.tga"}) {
        const std::string written = dir.path(name);
        WriteImage(written, 8, 8, 3, RandomTexels(rng, 8 * 8 * 3));
        error.clear();
        const bool opened = Open(written, &error) != nullptr;
        INFO(name << ": " << error);
        CHECK(opened);
    }
    // The error of opening `bytes` written to `path`, which must be refused.
    auto refusal = [&](const std::string& path, const std::string& bytes) {
        std::ofstream(path, std::ios::binary) << bytes;
        std::string why;
        CHECK_FALSE(Open(path, &why));
        return why;
    };
    // Only the formats of texture maps: the readers of others allocate what a damaged header
    // claims as they open it (fuzz/regressions/fuzz_texture/dpx_header_claims_2gb). Refused by
    // signature whatever the name, or by extension.
    const std::string readList =
        ", not a format affray reads texture maps from: TIFF, OpenEXR, PNG, JPEG, "
        "Radiance HDR, PNM, GIF or Targa (convert it, e.g. with oiiotool)";
    for (const auto& [name, bytes, expected] :
         {std::tuple<const char*, const char*, std::string>{"image.rla", "not an image\n", "RLA by its extension"},
          {"image.dpx", "not an image\n", "DPX by its extension"},
          {"dpx.png", "SDPX and more", "DPX by its signature"},
          {"photoshop.tif", "8BPS and more", "Photoshop by its signature"},
          {"bitmap.png", "BM and more", "BMP by its signature"}}) {
        const std::string other = dir.path(name);
        CHECK(refusal(other, bytes) == "cannot read texture '" + other + "': " + expected + readList);
    }

    // PNG files that end early (fuzz/regressions/fuzz_texture): refused, naming the file and
    // where it ends, before OpenImageIO reads them (image/image_io_oiio.cpp says why).
    const std::string signature = "\x89PNG\r\n\x1a\n";
    const std::string truncated = dir.path("truncated.png");
    std::ofstream(truncated, std::ios::binary) << signature;
    REQUIRE(std::filesystem::file_size(truncated) == 8);
    error.clear();
    CHECK_FALSE(Open(truncated, &error));
    CHECK(error == "cannot read texture '" + truncated + "': the PNG file ends at byte 8, before its IEND chunk");
    const std::string cut = dir.path("cut.png");
    WriteImage(cut, 8, 8, 3, RandomTexels(rng, 8 * 8 * 3));
    const std::string bytes = affray::test::ReadText(cut);
    REQUIRE(bytes.compare(0, 8, signature) == 0);
    REQUIRE(Open(cut, &error));
    // The signature decides, not the name: a PNG named .exr reads as the PNG it is.
    const std::string misnamed = dir.path("misnamed.exr");
    std::ofstream(misnamed, std::ios::binary) << bytes;
    error.clear();
    CHECK(Open(misnamed, &error));
    CHECK(error.empty());
    const std::string half = dir.path("half.png");
    std::ofstream(half, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    error.clear();
    CHECK_FALSE(Open(half, &error));
    CHECK(error.find("cannot read texture '" + half + "': the PNG chunk at byte ") == 0);
    CHECK(error.find("but the file has " + std::to_string(bytes.size() / 2)) != std::string::npos);

    // OpenEXR files whose header attributes claim more bytes than the file holds: refused before
    // OpenImageIO reads them (OpenEXR 3.1 would allocate the claim first; image/image_io_oiio.cpp).
    // A multi-part file (headers one after another) reads as usual.
    const std::string multipart = affray::test::SourceDir() + "/fuzz/corpus/fuzz_texture/multipart4x4.exr";
    REQUIRE(Open(multipart, &error));
    std::string exr = affray::test::ReadText(multipart);
    // The first attribute: its name and type after the 8 bytes of magic number and version, then
    // its size.
    const size_t nameEnd = exr.find('\0', 8), typeEnd = exr.find('\0', nameEnd + 1);
    REQUIRE(typeEnd != std::string::npos);
    const std::string attribute = exr.substr(8, nameEnd - 8);
    exr.replace(typeEnd + 1, 4, std::string("\xff\xff\xff\x7f", 4));
    const std::string claims = dir.path("claims.exr");
    std::ofstream(claims, std::ios::binary) << exr;
    error.clear();
    CHECK_FALSE(Open(claims, &error));
    CHECK(error == "cannot read texture '" + claims + "': the OpenEXR attribute '" + attribute +
                       "' claims 2147483647 bytes, but the file has " + std::to_string(exr.size() - typeEnd - 5) +
                       " left");
    // A name longer than 31 characters without the long-names flag: OpenEXR would stop at its
    // limit and read the rest as the next fields (fuzz/regressions/fuzz_texture), so it is refused.
    REQUIRE((static_cast<unsigned char>(exr[5]) & 0x04) == 0);
    std::string longName = exr;
    longName.replace(8, nameEnd - 8, std::string(40, 'n'));
    const std::string named = dir.path("named.exr");
    CHECK(refusal(named, longName) ==
          "cannot read texture '" + named +
              "': an OpenEXR attribute's name or type at byte 8 is longer than 31 characters");
    // With the flag, names up to 255 characters are read as the attribute they are.
    longName[5] = static_cast<char>(longName[5] | 0x04);
    const std::string flagged = refusal(named, longName);
    CHECK(flagged.find("longer than") == std::string::npos);
    CHECK(flagged.find("' claims 2147483647 bytes") != std::string::npos);

    // A channel of an unknown pixel type (OpenImageIO's reader would abort on it), or a channel
    // list that does not fill its stated size (OpenEXR reads channels until an empty name).
    const std::string original = affray::test::ReadText(multipart);
    const size_t chlist = original.find(std::string("channels\0chlist\0", 16));
    REQUIRE(chlist != std::string::npos);
    const size_t value = chlist + 16 + 4, channelEnd = original.find('\0', value);
    const std::string channel = original.substr(value, channelEnd - value);
    std::string badType = original;
    badType[channelEnd + 1] = 3;
    const std::string typed = dir.path("typed.exr");
    CHECK(refusal(typed, badType) == "cannot read texture '" + typed + "': the OpenEXR attribute 'channels' at byte " +
                                         std::to_string(value) + ": the channel '" + channel +
                                         "' has pixel type 3 (0, 1 and 2 are uint, half and float)");
    std::string shortList = original;
    shortList[value] = '\0';  // an empty first name: the list ends before its size
    CHECK(refusal(typed, shortList)
              .find("': the OpenEXR attribute 'channels' at byte " + std::to_string(value) +
                    ": its channels end before its size") != std::string::npos);

    // A value of a fixed-size type in another size: OpenEXR would read it in its own size and the
    // fields after it from other bytes (fuzz/regressions/fuzz_texture/exr_v2f_short_hides_2gb_string).
    const std::string widthAttribute("screenWindowWidth\0float\0", 24);
    const size_t widthAt = original.find(widthAttribute);
    REQUIRE(widthAt != std::string::npos);
    std::string shortFloat = original;
    shortFloat[widthAt + 24] = 1;
    CHECK(refusal(typed, shortFloat) == "cannot read texture '" + typed +
                                            "': the OpenEXR attribute 'screenWindowWidth' at byte " +
                                            std::to_string(widthAt + 28) + " has 1 bytes, where its type float has 4");

    // A preview whose 2^31 x 2^31 pixels would wrap a 64-bit product around to the 0 bytes it
    // holds: OpenEXR would allocate them first.
    std::string preview = original;
    preview.insert(8, std::string("preview\0preview\0\x08\0\0\0\0\0\0\x80\0\0\0\x80", 28));
    CHECK(refusal(typed, preview) == "cannot read texture '" + typed +
                                         "': the OpenEXR attribute 'preview' at byte 28: the preview image of "
                                         "2147483648 x 2147483648 pixels does not fill its 8 bytes");

    // GIF files whose canvas is larger than 2^26 pixels: refused before OpenImageIO, which would
    // allocate the canvas as it opens the file (or end the process when its size overflows an
    // int; fuzz/regressions/fuzz_texture).
    const std::string gif = dir.path("small.gif");
    WriteImage(gif, 8, 8, 3, RandomTexels(rng, 8 * 8 * 3));
    REQUIRE(Open(gif, &error));
    std::string gifBytes = affray::test::ReadText(gif);
    REQUIRE(gifBytes.compare(0, 4, "GIF8") == 0);
    gifBytes.replace(6, 4, std::string("\x72\x79\x00\x73", 4));
    const std::string huge = dir.path("huge.gif");
    CHECK(refusal(huge, gifBytes) ==
          "cannot read texture '" + huge +
              "': the GIF canvas of 31090 x 29440 pixels is larger than affray reads (67108864 pixels)");
    const std::string stub = dir.path("stub.gif");
    CHECK(refusal(stub, "GIF89a\x01") ==
          "cannot read texture '" + stub + "': the GIF file ends in its header, at byte 7");
}

TEST_CASE("texture file: tiles under a tiny budget give the same lookups, from several threads", "[texture]") {
    ScratchDir dir;
    Rng rng(16103);
    const int n = 1024;
    const std::vector<float> texels = RandomTexels(rng, static_cast<size_t>(n) * n);
    const std::string tiled = dir.path("big.exr"), scan = dir.path("big.tif");
    ImageLayout layout;
    layout.tile = 64;
    WriteImage(tiled, n, n, 1, texels, layout);
    WriteImage(scan, n, n, 1, texels);
    auto pixels = TextureMap::FromPixels(n, n, 1, texels);

    const size_t budget = TileMemoryBudget();
    SetTileMemoryBudget(64 << 10);
    const CacheStats before = Stats();
    std::string error;
    auto map = Open(tiled, &error);
    REQUIRE(map);
    auto scanMap = Open(scan, &error);
    REQUIRE(scanMap);

    // Random points (a tile each) and a coherent walk, with every filter.
    std::vector<std::pair<double, double>> points;
    points.reserve(1000);
    for (int i = 0; i < 1000; ++i) points.emplace_back(rng.uniform(-0.2, 1.2), rng.uniform(-0.2, 1.2));
    for (int i = 0; i < 3000; ++i) points.emplace_back(0.1 + i * 2.5e-4, 0.7 - i * 1e-4);
    LookupOptions o;
    int64_t differ = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        o.filter = static_cast<Filter>(i % 4);
        o.swrap = static_cast<Wrap>(i % 3);
        const auto [s, t] = points[i];
        const double want = Sample(pixels.get(), o, 0, s, t);
        if (Sample(map.get(), o, 0, s, t) != want) ++differ;
        if (i % 10 == 0 && Sample(scanMap.get(), o, 0, s, t) != want) ++differ;
    }
    CHECK(differ == 0);
    const CacheStats after = Stats();
    CHECK(after.tilesRead > before.tilesRead);
    CHECK(after.tilesDropped > before.tilesDropped);
    CHECK(after.residentBytes <= (64 << 10) + (64 * 64 * 4 + 256) * 2);
    CHECK(map->residentBytes() < static_cast<size_t>(n) * n);  // the pyramid and a few tiles

    // Several threads sampling the same map under the budget give the same values.
    SetTileMemoryBudget(256 << 10);
    std::vector<double> want(points.size());
    o = LookupOptions();
    o.filter = Filter::CatmullRom;
    for (size_t i = 0; i < points.size(); ++i) want[i] = Sample(pixels.get(), o, 0, points[i].first, points[i].second);
    std::vector<int64_t> threadDiffer(3, 0);
    std::vector<std::thread> threads;
    threads.reserve(3);
    for (int k = 0; k < 3; ++k) {
        threads.emplace_back([&, k] {
            for (size_t j = 0; j < points.size(); ++j) {
                const size_t i = (j * (k + 1) * 7919) % points.size();  // each thread its own order
                if (Sample(map.get(), o, 0, points[i].first, points[i].second) != want[i]) ++threadDiffer[k];
            }
        });
    }
    for (std::thread& t : threads) t.join();
    for (int64_t d : threadDiffer) CHECK(d == 0);

    // A budget of nothing drops every tile: the maps keep only their pyramids, and still read.
    const size_t withTiles = map->residentBytes();
    SetTileMemoryBudget(0);
    CHECK(Stats().residentBytes == 0);
    CHECK(map->residentBytes() < withTiles);
    CHECK(Sample(map.get(), o, 0, 0.3, 0.3) == Sample(pixels.get(), o, 0, 0.3, 0.3));

    SetTileMemoryBudget(budget);
    CHECK(TileMemoryBudget() == budget);
}

// Found by fuzz_texture (fuzz/regressions/fuzz_texture/pgm_huge_width.pgm): a header's sides went
// into int tile counts and band sizes unchecked, and overflowed.
TEST_CASE("texture file: a header with sides or tiles past 2^30 is refused, naming the file", "[texture]") {
    ScratchDir dir;
    auto open = [&](const std::string& name, const std::string& header) {
        const std::string path = dir.path(name);
        std::ofstream(path, std::ios::binary) << header << std::string(16, '\0');
        std::string error;
        CHECK_FALSE(Open(path, &error));
        return error;
    };
    // One side past 2^30; both sides at 2^30 (2^48 tiles).
    const std::string wide = open("wide.pgm", "P5\n2147483647 1\n255\n");
    CHECK(wide == "cannot read texture '" + dir.path("wide.pgm") +
                      "': the image is too large (2147483647 x 1 texels; sides and tile counts are limited to 2^30)");
    const std::string square = open("square.pgm", "P5\n1073741824 1073741824\n255\n");
    CHECK(square.find("'" + dir.path("square.pgm") + "': the image is too large (1073741824 x 1073741824") !=
          std::string::npos);
    // The fuzzer's input, as found.
    std::string error;
    CHECK_FALSE(Open(std::string(AFFRAY_SOURCE_DIR) + "/fuzz/regressions/fuzz_texture/pgm_huge_width.pgm", &error));
    CHECK(error.find("too large") != std::string::npos);
}
