// tests/renderer/film_test.cpp: the film (renderer/film.*): crop pixels that partition the image,
// sample positions that do not depend on who asks, filter weights worked out by hand, images
// that do not depend on the tiling bit for bit, the AOV rules and exposure. (Display modes are
// tests/scene/display_test.cpp's.)
#include "renderer/film.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <functional>

using namespace affray::renderer;
using affray::image::ImageBuffer;

namespace {

using SyntheticScene = std::function<SampleValue(const Sample&)>;

CameraDesc MakeCamera(int xres, int yres, FilterDesc::Kind kind = FilterDesc::Kind::Gaussian, double width = 2,
                      int xsamples = 2, int ysamples = 2) {
    CameraDesc c;
    c.xres = xres;
    c.yres = yres;
    c.filter.kind = kind;
    c.filter.xwidth = c.filter.ywidth = width;
    c.xsamples = xsamples;
    c.ysamples = ysamples;
    return c;
}

/// Renders `scene` tile by tile through the film, as render.cpp does (tiles in reverse order if
/// asked, to show that the order does not matter either).
ImageBuffer Render(const Film& film, int tileSize, const SyntheticScene& scene, bool reverse = false) {
    ImageBuffer image = film.MakeImage();
    std::vector<PixelRange> tiles = film.Tiles(tileSize);
    if (reverse) std::reverse(tiles.begin(), tiles.end());
    std::vector<Sample> samples;
    std::vector<SampleValue> values;
    for (const PixelRange& tile : tiles) {
        film.TileSamples(tile, &samples);
        values.resize(samples.size());
        for (size_t i = 0; i < samples.size(); ++i) values[i] = scene(samples[i]);
        film.ResolveTile(tile, samples, values, &image);
    }
    return image;
}

/// A scene whose every channel varies with the raster position, with hits and misses.
SampleValue Wavy(const Sample& s) {
    SampleValue v;
    const double x = s.raster.x, y = s.raster.y;
    if (std::sin(0.3 * x) + std::cos(0.21 * y) < 0.4) return v;  // a miss
    v.rgb = {0.5 + 0.5 * std::sin(x * 0.37), 0.5 + 0.5 * std::cos(y * 0.53), std::fmod(x * y, 1.0)};
    v.alpha = 1;
    v.z = 3 + x / 7 + y * y / 100;
    v.N = glm::normalize(glm::dvec3(std::sin(x), std::cos(y), 1));
    v.P = {x, y, v.z};
    v.st = {x / 40, y / 30};
    v.cost = static_cast<int>(x * 13 + y * 7) % 29;
    v.err = 1e-4 * std::fabs(std::sin(x * y));
    return v;
}

bool BitIdentical(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

void RequireBitIdentical(const ImageBuffer& a, const ImageBuffer& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    REQUIRE(BitIdentical(a.rgba, b.rgba));
    REQUIRE(a.extraChannels.size() == b.extraChannels.size());
    for (size_t c = 0; c < a.extraChannels.size(); ++c) {
        INFO("channel " << a.extraChannels[c].first);
        REQUIRE(a.extraChannels[c].first == b.extraChannels[c].first);
        REQUIRE(BitIdentical(a.extraChannels[c].second, b.extraChannels[c].second));
    }
}

const std::vector<float>& Channel(const ImageBuffer& image, const std::string& name) {
    for (const auto& [n, values] : image.extraChannels)
        if (n == name) return values;
    FAIL("no channel " << name);
    throw 0;  // not reached
}

DisplayChannels AllChannels() { return {true, true, true, true, true, true}; }

}  // namespace

TEST_CASE("Crop windows give the RI pixel rectangles", "[film]") {
    CameraDesc c = MakeCamera(640, 480);
    CHECK(CropPixels(c) == PixelRange{0, 640, 0, 480});  // the default window is the whole frame
    c.cropWindow = {0.25, 0.75, 0.5, 1.0};
    // ceil(640 * 0.25 - 0.5) = 160, ceil(480 - 0.5) = 480, ceil(240 - 0.5) = 240.
    CHECK(CropPixels(c) == PixelRange{160, 480, 240, 480});
    c = MakeCamera(101, 7);
    c.cropWindow = {0.0, 0.5, 0.5, 1.0};
    // x: ceil(50.5 - 0.5) = 50; y: ceil(3.5 - 0.5) = 3.
    CHECK(CropPixels(c) == PixelRange{0, 50, 3, 7});
    c.cropWindow = {0.6, 0.4, 0.0, 1.0};  // backwards: empty, not negative
    CHECK(CropPixels(c).empty());
}

TEST_CASE("Crops of a partition of the frame partition the pixels", "[film]") {
    const std::vector<std::vector<double>> cuts = {
        {0, 0.5, 1}, {0, 1.0 / 3, 2.0 / 3, 1}, {0, 0.1, 0.25, 0.7, 0.95, 1}, {0, 0.001, 1}};
    for (int res : {1, 2, 7, 100, 101, 333, 640}) {
        for (const auto& xs : cuts)
            for (const auto& ys : cuts) {
                std::vector<int> covered(static_cast<size_t>(res) * res, 0);
                for (size_t i = 0; i + 1 < xs.size(); ++i)
                    for (size_t j = 0; j + 1 < ys.size(); ++j) {
                        CameraDesc c = MakeCamera(res, res);
                        c.cropWindow = {xs[i], xs[i + 1], ys[j], ys[j + 1]};
                        PixelRange r = CropPixels(c);
                        for (int y = r.y0; y < r.y1; ++y)
                            for (int x = r.x0; x < r.x1; ++x) ++covered[static_cast<size_t>(y) * res + x];
                    }
                INFO("resolution " << res << ", " << xs.size() - 1 << " x " << ys.size() - 1 << " crops");
                REQUIRE(std::count(covered.begin(), covered.end(), 1) == static_cast<std::ptrdiff_t>(res) * res);
            }
    }
}

TEST_CASE("Samples depend only on their pixel, index and seed", "[film]") {
    Film film(MakeCamera(40, 30, FilterDesc::Kind::Gaussian, 2, 3, 2));
    REQUIRE(film.samplesPerPixel() == 6);
    std::vector<Sample> a, b;
    film.TileSamples({0, 8, 0, 8}, &a);
    film.TileSamples({5, 13, 5, 13}, &b);
    auto find = [](const std::vector<Sample>& v, int px, int py, int k) {
        for (const Sample& s : v)
            if (s.px == px && s.py == py && s.index == k) return s.raster;
        FAIL("sample not found");
        return glm::dvec2(0.0);
    };
    // Pixel (6, 7) is inside the first tile and the second's; (8, 8) only in the first's margin.
    for (int k = 0; k < 6; ++k) {
        CHECK(find(a, 6, 7, k) == find(b, 6, 7, k));
        CHECK(find(a, 8, 8, k) == find(b, 8, 8, k));
        CHECK(find(a, 8, 8, k) == film.SamplePosition(8, 8, k));
    }
    // A crop film has the same samples as the whole film.
    CameraDesc cropped = MakeCamera(40, 30, FilterDesc::Kind::Gaussian, 2, 3, 2);
    cropped.cropWindow = {0.3, 0.6, 0.1, 0.9};
    Film cropFilm(cropped);
    for (int k = 0; k < 6; ++k) CHECK(cropFilm.SamplePosition(13, 9, k) == film.SamplePosition(13, 9, k));
    // Another seed moves them.
    Film reseeded(MakeCamera(40, 30, FilterDesc::Kind::Gaussian, 2, 3, 2), {}, 7);
    CHECK(reseeded.SamplePosition(13, 9, 0) != film.SamplePosition(13, 9, 0));
}

TEST_CASE("Each sample lies in its own stratum of its pixel", "[film]") {
    Film film(MakeCamera(9, 5, FilterDesc::Kind::Box, 1, 3, 4));
    std::vector<Sample> samples;
    film.TileSamples({0, 9, 0, 5}, &samples);
    REQUIRE(samples.size() == size_t{9} * 5 * 12);
    for (const Sample& s : samples) {
        const int i = s.index % 3, j = s.index / 3;
        INFO("pixel " << s.px << "," << s.py << " sample " << s.index);
        CHECK(s.raster.x >= s.px + i / 3.0);
        CHECK(s.raster.x < s.px + (i + 1) / 3.0);
        CHECK(s.raster.y >= s.py + j / 4.0);
        CHECK(s.raster.y < s.py + (j + 1) / 4.0);
    }
}

TEST_CASE("Without jitter each sample lies at its stratum's centre", "[film]") {
    // Hider "hidden" "jitter" [0]: with PixelSamples 1 1 the ray through each pixel centre.
    CameraDesc one = MakeCamera(5, 4, FilterDesc::Kind::Box, 1, 1, 1);
    one.jitter = false;
    Film film(one, {}, 12345);
    for (int py = 0; py < 4; ++py)
        for (int px = 0; px < 5; ++px) CHECK(film.SamplePosition(px, py, 0) == glm::dvec2(px + 0.5, py + 0.5));
    // 2 x 4 strata: centres at 1/4, 3/4 across and 1/8, 3/8, 5/8, 7/8 down, row by row.
    CameraDesc many = MakeCamera(3, 3, FilterDesc::Kind::Box, 1, 2, 4);
    many.jitter = false;
    Film strata(many);
    for (int k = 0; k < 8; ++k) {
        const int column = k % 2, row = k / 2;
        CHECK(strata.SamplePosition(2, 1, k) == glm::dvec2(2 + (column * 2 + 1) / 4.0, 1 + (row * 2 + 1) / 8.0));
    }
    // The seed no longer matters.
    CHECK(Film(one, {}, 1).SamplePosition(3, 2, 0) == Film(one, {}, 2).SamplePosition(3, 2, 0));
}

TEST_CASE("Tile sample regions grow by the filter margin and stop at the image", "[film]") {
    CHECK(Film(MakeCamera(20, 20, FilterDesc::Kind::Box, 1)).marginX() == 0);
    CHECK(Film(MakeCamera(20, 20, FilterDesc::Kind::Gaussian, 2)).marginX() == 1);  // |p - q| < 1.5
    CHECK(Film(MakeCamera(20, 20, FilterDesc::Kind::Gaussian, 3)).marginX() == 1);  // |p - q| < 2
    CHECK(Film(MakeCamera(20, 20, FilterDesc::Kind::Gaussian, 4)).marginX() == 2);  // |p - q| < 2.5
    CameraDesc wide = MakeCamera(20, 20, FilterDesc::Kind::Gaussian, 4);
    wide.filter.ywidth = 2;
    Film film(wide);
    CHECK(film.marginX() == 2);
    CHECK(film.marginY() == 1);
    CHECK(film.SampleRegion({0, 4, 0, 4}) == PixelRange{0, 6, 0, 5});
    CHECK(film.SampleRegion({8, 12, 16, 20}) == PixelRange{6, 14, 15, 20});
}

TEST_CASE("Tiles cover the crop window exactly once", "[film]") {
    CameraDesc c = MakeCamera(50, 40);
    c.cropWindow = {0.1, 0.9, 0.25, 0.5};
    Film film(c);
    const PixelRange crop = film.crop();
    for (int size : {1, 7, 16, 64}) {
        std::vector<int> covered(size_t{50} * 40, 0);
        for (const PixelRange& t : film.Tiles(size)) {
            CHECK(t.width() <= size);
            for (int y = t.y0; y < t.y1; ++y)
                for (int x = t.x0; x < t.x1; ++x) ++covered[y * 50 + x];
        }
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 50; ++x) REQUIRE(covered[y * 50 + x] == (crop.Contains(x, y) ? 1 : 0));
    }
}

TEST_CASE("Filter weights match RI appendix E", "[film]") {
    Film gauss(MakeCamera(8, 8, FilterDesc::Kind::Gaussian, 2));
    CHECK(gauss.FilterWeight(0, 0) == 1);
    CHECK(gauss.FilterWeight(0.5, 0) == Approx(std::exp(-0.5)));     // x' = 0.5: exp(-2 * 0.25)
    CHECK(gauss.FilterWeight(0.5, -0.5) == Approx(std::exp(-1.0)));  // exp(-2 * (0.25 + 0.25))
    CHECK(gauss.FilterWeight(-1, 0) == Approx(std::exp(-2.0)));      // the edge is in ...
    CHECK(gauss.FilterWeight(1, 0) == 0);                            // ... on one side only
    CHECK(gauss.FilterWeight(0, 1.2) == 0);

    CameraDesc c = MakeCamera(8, 8, FilterDesc::Kind::Gaussian, 4);
    c.filter.ywidth = 1;
    Film stretched(c);
    CHECK(stretched.FilterWeight(1, 0) == Approx(std::exp(-0.5)));     // x' = 1 / 2
    CHECK(stretched.FilterWeight(0, 0.25) == Approx(std::exp(-0.5)));  // y' = 0.25 / 0.5
    CHECK(stretched.FilterWeight(0, 0.5) == 0);

    Film box(MakeCamera(8, 8, FilterDesc::Kind::Box, 1));
    CHECK(box.FilterWeight(-0.5, -0.5) == 1);
    CHECK(box.FilterWeight(0.49, 0.2) == 1);
    CHECK(box.FilterWeight(0.5, 0) == 0);
}

TEST_CASE("A constant image resolves to its colour under both filters", "[film]") {
    auto constant = [](const Sample&) {
        SampleValue v;
        v.rgb = {0.25, 0.5, 0.75};
        v.alpha = 1;
        return v;
    };
    for (auto kind : {FilterDesc::Kind::Box, FilterDesc::Kind::Gaussian})
        for (double width : {1.0, 2.0, 3.5}) {
            Film film(MakeCamera(13, 9, kind, width, 3, 3));
            ImageBuffer image = Render(film, 4, constant);
            for (size_t p = 0; p < size_t{13} * 9; ++p) {
                INFO("pixel " << p << " width " << width);
                // Normalising by the weight sum makes the edge pixels, with clipped footprints, exact too.
                REQUIRE(image.rgba[p * 4 + 0] == Approx(0.25f));
                REQUIRE(image.rgba[p * 4 + 1] == Approx(0.5f));
                REQUIRE(image.rgba[p * 4 + 2] == Approx(0.75f));
                REQUIRE(image.rgba[p * 4 + 3] == Approx(1.0f));
            }
        }
}

TEST_CASE("Images do not depend on the tile size or order, bit for bit", "[film]") {
    for (auto kind : {FilterDesc::Kind::Box, FilterDesc::Kind::Gaussian}) {
        Film film(MakeCamera(37, 23, kind, kind == FilterDesc::Kind::Box ? 3 : 2, 3, 2), AllChannels());
        ImageBuffer one = Render(film, 1, Wavy);
        RequireBitIdentical(one, Render(film, 16, Wavy));
        RequireBitIdentical(one, Render(film, 64, Wavy));
        RequireBitIdentical(one, Render(film, 5, Wavy, true));
    }
}

TEST_CASE("A crop render has the whole render's pixels inside the crop and zero outside", "[film]") {
    CameraDesc whole = MakeCamera(30, 20);
    ImageBuffer reference = Render(Film(whole, AllChannels()), 8, Wavy);
    ImageBuffer merged;
    const double cuts[] = {0, 0.5, 1};
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            CameraDesc c = whole;
            c.cropWindow = {cuts[i], cuts[i + 1], cuts[j], cuts[j + 1]};
            Film film(c, AllChannels());
            ImageBuffer crop = Render(film, 8, Wavy);
            const PixelRange r = film.crop();
            for (int y = 0; y < 20; ++y)
                for (int x = 0; x < 30; ++x) {
                    const size_t p = static_cast<size_t>(y) * 30 + x;
                    for (int k = 0; k < 4; ++k)
                        REQUIRE(crop.rgba[p * 4 + k] == (r.Contains(x, y) ? reference.rgba[p * 4 + k] : 0.0f));
                    for (size_t ch = 0; ch < crop.extraChannels.size(); ++ch)
                        REQUIRE(crop.extraChannels[ch].second[p] ==
                                (r.Contains(x, y) ? reference.extraChannels[ch].second[p] : 0.0f));
                }
            std::string error;
            REQUIRE(PasteCrop(crop, r, &merged, &error));
        }
    RequireBitIdentical(merged, reference);
    std::string error;
    ImageBuffer small = Film(MakeCamera(4, 4)).MakeImage();
    CHECK_FALSE(PasteCrop(small, {0, 4, 0, 4}, &merged, &error));
    CHECK(error.find("4x4") != std::string::npos);
}

TEST_CASE("MakeImage names the AOV channels the display mode asks for", "[film]") {
    Film plain(MakeCamera(5, 3));
    ImageBuffer image = plain.MakeImage();
    CHECK(image.width == 5);
    CHECK(image.height == 3);
    CHECK(image.rgba.size() == 60u);
    CHECK(image.extraChannels.empty());

    ImageBuffer all = Film(MakeCamera(5, 3), AllChannels()).MakeImage();
    std::vector<std::string> names;
    for (const auto& [name, values] : all.extraChannels) {
        names.push_back(name);
        CHECK(values.size() == 15u);
    }
    CHECK(names ==
          std::vector<std::string>{"Z", "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "st.s", "st.t", "cost", "err"});
}

TEST_CASE("Z N P st come from the nearest own sample, cost sums and err maxes", "[film]") {
    // A 3x3 image; the centre pixel's samples carry small values, every other pixel's huge ones,
    // so any leak from the gaussian's neighbours into the unfiltered channels would show.
    Film film(MakeCamera(3, 3, FilterDesc::Kind::Gaussian, 2, 2, 2), AllChannels());
    auto scene = [](const Sample& s) {
        SampleValue v;
        const bool centre = s.px == 1 && s.py == 1;
        v.rgb = glm::dvec3(centre ? 1.0 : 0.0);
        v.alpha = centre ? 1 : 0;
        v.z = centre ? 10 + s.index : 1e6;
        v.N = glm::dvec3(0, 0, centre ? s.index : 99);
        v.P = glm::dvec3(centre ? s.index : 99, 0, 0);
        v.st = glm::dvec2(centre ? 0.25 * s.index : 99, 0.5);
        v.cost = centre ? s.index + 1 : 1000;
        v.err = centre ? 0.5 * s.index : 1e3;
        return v;
    };
    ImageBuffer image = Render(film, 2, scene);
    int nearest = 0;
    double best = INFINITY;
    for (int k = 0; k < 4; ++k) {
        glm::dvec2 d = film.SamplePosition(1, 1, k) - glm::dvec2(1.5, 1.5);
        if (glm::dot(d, d) < best) best = glm::dot(d, d), nearest = k;
    }
    const size_t centre = 4;
    CHECK(Channel(image, "Z")[centre] == 10.0f + nearest);
    CHECK(Channel(image, "N.Z")[centre] == float(nearest));
    CHECK(Channel(image, "P.X")[centre] == float(nearest));
    CHECK(Channel(image, "st.s")[centre] == 0.25f * nearest);
    CHECK(Channel(image, "st.t")[centre] == 0.5f);
    CHECK(Channel(image, "cost")[centre] == 1 + 2 + 3 + 4);
    CHECK(Channel(image, "err")[centre] == 1.5f);
    // RGBA are filtered: the centre pixel sees black neighbours, the corner sees some of the centre.
    CHECK(image.rgba[centre * 4] > 0.0f);
    CHECK(image.rgba[centre * 4] < 1.0f);
    CHECK(image.rgba[0] > 0.0f);
    CHECK(Channel(image, "cost")[0] == 4000);
}

TEST_CASE("Misses give no-hit depth, zero AOVs and alpha 0", "[film]") {
    Film film(MakeCamera(4, 4, FilterDesc::Kind::Box, 1, 2, 2), AllChannels());
    auto halfHit = [](const Sample& s) {  // in every pixel, samples 0 and 3 hit
        SampleValue v;
        if (s.index == 1 || s.index == 2) return v;
        v.rgb = {1, 0.5, 0};
        v.alpha = 1;
        v.z = 2;
        return v;
    };
    ImageBuffer half = Render(film, 4, halfHit);
    CHECK(half.rgba[0] == 0.5f);  // box of width 1: the mean of the pixel's own four samples
    CHECK(half.rgba[1] == 0.25f);
    CHECK(half.rgba[3] == 0.5f);
    ImageBuffer empty = Render(film, 4, [](const Sample&) { return SampleValue{}; });
    CHECK(Channel(empty, "Z")[5] == static_cast<float>(kNoHitDepth));
    CHECK(Channel(empty, "N.X")[5] == 0.0f);
    CHECK(empty.rgba[5 * 4 + 3] == 0.0f);
}

TEST_CASE("Exposure maps colour through gain and gamma", "[film]") {
    auto grey = [](const Sample&) {
        SampleValue v;
        v.rgb = glm::dvec3(0.125);
        v.alpha = 1;
        return v;
    };
    CameraDesc c = MakeCamera(2, 2, FilterDesc::Kind::Box, 1);
    c.exposureGain = 2;
    c.exposureGamma = 2;
    ImageBuffer image = Render(Film(c), 2, grey);
    CHECK(image.rgba[0] == Approx(0.5));  // (2 * 0.125)^(1/2)
    CHECK(image.rgba[3] == 1.0f);         // alpha is not exposed
    CHECK(Film(c).Expose(-1) == 0);
    c.exposureGain = 3;
    c.exposureGamma = 1;
    CHECK(Film(c).Expose(0.1) == Approx(0.3));
    CHECK(Film(c).Expose(-0.1) == Approx(-0.3));  // gamma 1 is linear, negatives included
}

TEST_CASE("A pixel's samples take every lens stratum once, in an order of their own", "[film]") {
    for (const auto& [xs, ys] : {std::pair{1, 1}, std::pair{4, 4}, std::pair{3, 5}, std::pair{8, 8}}) {
        Film film(MakeCamera(6, 4, FilterDesc::Kind::Box, 1, xs, ys), {}, 3);
        const int n = xs * ys;
        int sameOrder = 0;
        std::vector<int> firstPixel;
        for (int py = 0; py < 4; ++py)
            for (int px = 0; px < 6; ++px) {
                std::vector<int> count(size_t(n), 0), order;
                for (int k = 0; k < n; ++k) {
                    const glm::dvec2 u = film.LensPosition(px, py, k);
                    INFO(xs << "x" << ys << " pixel " << px << "," << py << " sample " << k);
                    REQUIRE((u.x >= 0 && u.x < 1 && u.y >= 0 && u.y < 1));
                    const int stratum = int(u.y * ys) * xs + int(u.x * xs);
                    ++count[size_t(stratum)];
                    order.push_back(stratum);
                    CHECK(film.LensPosition(px, py, k) == u);  // the same whoever asks
                }
                for (int c : count) CHECK(c == 1);
                if (firstPixel.empty())
                    firstPixel = order;
                else
                    sameOrder += order == firstPixel;
            }
        // The order is shuffled per pixel (else the lens stratum would follow the pixel stratum).
        if (n >= 16) CHECK(sameOrder == 0);
    }
}
