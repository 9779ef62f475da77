// renderer/film.cpp: crop window, sample positions, filtering and AOV rules (see film.h).
#include "renderer/film.h"
#include "diag/check.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace affray::renderer {

namespace {

/// splitmix64's finaliser (Steele, Lea, Flood, "Fast splittable pseudorandom number
/// generators", OOPSLA 2014): every input bit affects every output bit.
std::uint64_t Mix64(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// One RI crop edge: the first pixel whose centre lies at or past ndc * res, clamped.
int CropEdge(double ndc, int res) {
    double edge = std::ceil(res * ndc - 0.5);
    return static_cast<int>(std::clamp(edge, 0.0, static_cast<double>(res)));
}

/// Pixels a sample may lie from a pixel it reaches: samples of pixel p lie in [p, p+1), a pixel
/// q takes those within h of its centre q + 0.5, so |p - q| < h + 0.5.
int MarginFor(double halfWidth) { return std::max(0, static_cast<int>(std::ceil(halfWidth + 0.5)) - 1); }

/// The extra channels of an image, by role; null where the image lacks one.
struct ChannelPointers {
    float* z = nullptr;
    float* n[3] = {nullptr, nullptr, nullptr};
    float* p[3] = {nullptr, nullptr, nullptr};
    float* st[2] = {nullptr, nullptr};
    float* cost = nullptr;
    float* err = nullptr;
};

ChannelPointers FindChannels(image::ImageBuffer* image) {
    ChannelPointers c;
    const struct {
        const char* name;
        float** slot;
    } table[] = {{"Z", &c.z},        {"N.X", &c.n[0]},  {"N.Y", &c.n[1]}, {"N.Z", &c.n[2]},
                 {"P.X", &c.p[0]},   {"P.Y", &c.p[1]},  {"P.Z", &c.p[2]}, {"st.s", &c.st[0]},
                 {"st.t", &c.st[1]}, {"cost", &c.cost}, {"err", &c.err}};
    const size_t pixels = static_cast<size_t>(image->width) * image->height;
    for (auto& [name, values] : image->extraChannels)
        for (const auto& entry : table)
            if (name == entry.name && values.size() == pixels) *entry.slot = values.data();
    return c;
}

/// What a pixel gathers from the samples of its footprint, before normalising.
struct PixelSums {
    double weight = 0, alpha = 0;
    glm::dvec3 rgb{0.0};
    const SampleValue* nearest = nullptr;  // own sample nearest the centre
    double nearestDistance2 = INFINITY;
    std::int64_t cost = 0;
    double err = 0;
};

/// Sums what pixel (x, y) takes from the samples of its footprint. The footprint is visited in an
/// order that depends on the pixel and the image only, never on the tile: this is what makes every
/// tiling give the same bits. `region` is the tile's SampleRegion, the layout of samples/values.
PixelSums Gather(const Film& film, int x, int y, const PixelRange& region, const std::vector<Sample>& samples,
                 const std::vector<SampleValue>& values) {
    const int spp = film.samplesPerPixel();
    const double cx = x + 0.5, cy = y + 0.5;
    PixelSums sums;
    for (int qy = std::max(y - film.marginY(), 0); qy <= std::min(y + film.marginY(), film.yres() - 1); ++qy)
        for (int qx = std::max(x - film.marginX(), 0); qx <= std::min(x + film.marginX(), film.xres() - 1); ++qx) {
            const size_t base = (static_cast<size_t>(qy - region.y0) * region.width() + (qx - region.x0)) * spp;
            const bool own = qx == x && qy == y;
            for (int k = 0; k < spp; ++k) {
                const SampleValue& v = values[base + k];
                const double dx = samples[base + k].raster.x - cx, dy = samples[base + k].raster.y - cy;
                const double w = film.FilterWeight(dx, dy);
                if (w > 0) {
                    sums.weight += w;
                    sums.rgb += w * v.rgb;
                    sums.alpha += w * v.alpha;
                }
                if (!own) continue;
                // Unfiltered channels: the own sample nearest the centre (the first one on ties).
                const double d2 = dx * dx + dy * dy;
                if (d2 < sums.nearestDistance2) {
                    sums.nearestDistance2 = d2;
                    sums.nearest = &v;
                }
                sums.cost += v.cost;
                if (v.err > sums.err) sums.err = v.err;
            }
        }
    return sums;
}

/// Normalises and exposes `sums` into pixel number `pixel` of every channel the image has.
void WritePixel(const Film& film, const PixelSums& sums, size_t pixel, const ChannelPointers& ch,
                image::ImageBuffer* image) {
    float* rgba = &image->rgba[pixel * 4];
    const double norm = sums.weight > 0 ? 1.0 / sums.weight : 0.0;
    glm::dvec3 rgb = sums.rgb * norm;
    double alpha = sums.alpha * norm;
    if (const std::optional<glm::dvec3>& background = film.Background()) {
        // Imager "background", before the exposure (RI 3.2's imaging pipeline).
        rgb += (1.0 - alpha) * *background;
        alpha = 1;
    }
    for (int c = 0; c < 3; ++c) rgba[c] = static_cast<float>(film.Expose(rgb[c]));
    rgba[3] = static_cast<float>(alpha);

    const SampleValue none;  // a pixel without samples reads as a miss
    const SampleValue& n = sums.nearest ? *sums.nearest : none;
    if (ch.z) ch.z[pixel] = static_cast<float>(n.z);
    for (int c = 0; c < 3; ++c) {
        if (ch.n[c]) ch.n[c][pixel] = static_cast<float>(n.N[c]);
        if (ch.p[c]) ch.p[c][pixel] = static_cast<float>(n.P[c]);
    }
    for (int c = 0; c < 2; ++c)
        if (ch.st[c]) ch.st[c][pixel] = static_cast<float>(n.st[c]);
    if (ch.cost) ch.cost[pixel] = static_cast<float>(sums.cost);
    if (ch.err) ch.err[pixel] = static_cast<float>(sums.err);
}

}  // namespace

std::vector<std::string> ChannelNames(const DisplayChannels& ch) {
    std::vector<std::string> names;
    if (ch.z) names.push_back("Z");
    if (ch.n) names.insert(names.end(), {"N.X", "N.Y", "N.Z"});
    if (ch.p) names.insert(names.end(), {"P.X", "P.Y", "P.Z"});
    if (ch.st) names.insert(names.end(), {"st.s", "st.t"});
    if (ch.cost) names.push_back("cost");
    if (ch.err) names.push_back("err");
    return names;
}

std::string ToString(const PixelRange& r) {
    return "[" + std::to_string(r.x0) + "," + std::to_string(r.x1) + ")x[" + std::to_string(r.y0) + "," +
           std::to_string(r.y1) + ")";
}

PixelRange CropPixels(const CameraDesc& camera) {
    const glm::dvec4& w = camera.cropWindow;
    PixelRange r{CropEdge(w.x, camera.xres), CropEdge(w.y, camera.xres), CropEdge(w.z, camera.yres),
                 CropEdge(w.w, camera.yres)};
    // A window given backwards covers nothing rather than a negative rectangle.
    r.x1 = std::max(r.x1, r.x0);
    r.y1 = std::max(r.y1, r.y0);
    return r;
}

std::uint64_t SampleHash(int x, int y, int index, std::uint64_t seed) {
    // Chained so that (x, y) and (y, x) differ; each stage mixes fully before the next key word.
    std::uint64_t h = Mix64(seed ^ static_cast<std::uint32_t>(x));
    h = Mix64(h ^ static_cast<std::uint32_t>(y));
    return Mix64(h ^ static_cast<std::uint32_t>(index));
}

namespace {

/// The two 32-bit halves of the hash `h` as jitters in [0, 1): exact in a double, so a sample
/// stays in its stratum.
glm::dvec2 HashJitter(std::uint64_t h) {
    return {static_cast<double>(h >> 32) * 0x1p-32, static_cast<double>(h & 0xffffffffull) * 0x1p-32};
}

}  // namespace

Film::Film(const CameraDesc& camera, const DisplayChannels& channels, std::uint64_t seed)
    : m_xres(std::max(camera.xres, 0)),
      m_yres(std::max(camera.yres, 0)),
      m_crop(CropPixels(camera)),
      m_xsamples(std::max(camera.xsamples, 1)),
      m_ysamples(std::max(camera.ysamples, 1)),
      m_jitter(camera.jitter),
      m_filter(camera.filter),
      m_halfX(std::max(camera.filter.xwidth, 1.0) / 2),
      m_halfY(std::max(camera.filter.ywidth, 1.0) / 2),
      m_marginX(MarginFor(m_halfX)),
      m_marginY(MarginFor(m_halfY)),
      m_gain(camera.exposureGain),
      m_gamma(camera.exposureGamma),
      m_background(camera.background),
      m_channels(channels),
      m_seed(seed),
      m_lens(LensP(camera)),
      m_shutter(ShutterOpenP(camera)) {}

std::vector<PixelRange> Film::Tiles(int tileSize) const {
    tileSize = std::max(tileSize, 1);
    std::vector<PixelRange> tiles;
    for (int y = m_crop.y0; y < m_crop.y1; y += tileSize)
        for (int x = m_crop.x0; x < m_crop.x1; x += tileSize)
            tiles.push_back({x, std::min(x + tileSize, m_crop.x1), y, std::min(y + tileSize, m_crop.y1)});
    return tiles;
}

PixelRange Film::SampleRegion(const PixelRange& tile) const {
    return {std::max(tile.x0 - m_marginX, 0), std::min(tile.x1 + m_marginX, m_xres), std::max(tile.y0 - m_marginY, 0),
            std::min(tile.y1 + m_marginY, m_yres)};
}

glm::dvec2 Film::SamplePosition(int px, int py, int index) const {
    const int i = index % m_xsamples, j = index / m_xsamples;
    if (!m_jitter) return {px + (i + 0.5) / m_xsamples, py + (j + 0.5) / m_ysamples};
    const glm::dvec2 jitter = HashJitter(SampleHash(px, py, index, m_seed));
    return {px + (i + jitter.x) / m_xsamples, py + (j + jitter.y) / m_ysamples};
}

namespace {

/// Element `i` of a permutation of [0, n) chosen by `key`: a bijection of [0, 2^k) (2^k >= n) made
/// of invertible steps (xor with a key word, multiplication by an odd number, xor of the high bits
/// into the low ones, all modulo 2^k), walked until it lands below n (which keeps it a
/// bijection of [0, n)).
uint32_t Permuted(uint32_t i, uint32_t n, uint64_t key) {
    if (n <= 1) return 0;
    uint32_t mask = n - 1;
    for (int s = 1; s < 32; s <<= 1) mask |= mask >> s;
    const uint32_t k0 = uint32_t(key), k1 = uint32_t(key >> 32) | 1u;
    int bits = 0;
    while ((mask >> bits) != 0) ++bits;
    const int half = std::max(bits / 2, 1);
    do {
        i ^= k0;
        i &= mask;
        i = (i * k1) & mask;
        i ^= (i & mask) >> half;
        i = (i * 0x2c1b3c6dU) & mask;
        i ^= (k0 >> 7) & mask;
        i = (i * ((k1 ^ 0x297a2d38U) | 1u)) & mask;
        i ^= i >> half;
    } while (i >= n);
    return i;
}

/// Where sample `index` of pixel (px, py) falls among the pixel's `n` strata of a lens or shutter
/// dimension: its stratum, in an order shuffled per pixel, and its jitter within the stratum in
/// [0, 1) (0.5 without jitter). `key` keeps the dimensions' orders and jitters apart.
struct Stratum {
    uint32_t index;
    glm::dvec2 jitter;
};
Stratum ShuffledStratum(int px, int py, int index, uint32_t n, uint64_t seed, uint64_t key, bool jitter) {
    const uint32_t stratum = Permuted(uint32_t(index), n, SampleHash(px, py, -1, seed ^ key));
    if (!jitter) return {stratum, glm::dvec2(0.5)};
    return {stratum, HashJitter(SampleHash(px, py, index, seed ^ key))};
}

}  // namespace

glm::dvec2 Film::LensPosition(int px, int py, int index) const {
    constexpr uint64_t kKey = 0x6c656e73ull;  // "lens"
    const uint32_t n = uint32_t(m_xsamples) * uint32_t(m_ysamples);
    const Stratum s = ShuffledStratum(px, py, index, n, m_seed, kKey, m_jitter);
    const int i = int(s.index % uint32_t(m_xsamples)), j = int(s.index / uint32_t(m_xsamples));
    return {(i + s.jitter.x) / m_xsamples, (j + s.jitter.y) / m_ysamples};
}

double Film::TimePosition(int px, int py, int index) const {
    constexpr uint64_t kKey = 0x74696d65ull;  // "time": strata and jitter apart from the lens's
    const uint32_t n = uint32_t(m_xsamples) * uint32_t(m_ysamples);
    const Stratum s = ShuffledStratum(px, py, index, n, m_seed, kKey, m_jitter);
    return (s.index + s.jitter.x) / n;
}

void Film::TileSamples(const PixelRange& tile, std::vector<Sample>* out) const {
    const PixelRange region = SampleRegion(tile);
    const int spp = samplesPerPixel();
    out->clear();
    if (region.empty()) return;
    out->reserve(static_cast<size_t>(region.width()) * region.height() * spp);
    for (int py = region.y0; py < region.y1; ++py)
        for (int px = region.x0; px < region.x1; ++px)
            for (int k = 0; k < spp; ++k)
                out->push_back({px, py, k, SamplePosition(px, py, k),
                                m_lens ? LensPosition(px, py, k) : glm::dvec2(0.5),
                                m_shutter ? TimePosition(px, py, k) : 0.0});
}

double Film::FilterWeight(double dx, double dy) const {
    if (!(dx >= -m_halfX && dx < m_halfX && dy >= -m_halfY && dy < m_halfY)) return 0;
    if (m_filter.kind == FilterDesc::Kind::Box) return 1;
    const double x = dx / m_halfX, y = dy / m_halfY;
    return std::exp(-2.0 * (x * x + y * y));
}

double Film::Expose(double c) const {
    if (m_gamma == 1) return m_gain * c;
    return std::pow(std::max(m_gain * c, 0.0), 1.0 / m_gamma);
}

image::ImageBuffer Film::MakeImage() const {
    image::ImageBuffer image;
    image.width = m_xres;
    image.height = m_yres;
    const size_t pixels = static_cast<size_t>(m_xres) * m_yres;
    image.rgba.assign(pixels * 4, 0.0f);
    for (const std::string& name : ChannelNames(m_channels))
        image.extraChannels.emplace_back(name, std::vector<float>(pixels, 0.0f));
    return image;
}

void Film::ResolveTile(const PixelRange& tile, const std::vector<Sample>& samples,
                       const std::vector<SampleValue>& values, image::ImageBuffer* image) const {
    const PixelRange region = SampleRegion(tile);
    const size_t expected =
        region.empty() ? 0 : static_cast<size_t>(region.width()) * region.height() * samplesPerPixel();
    // The tile's samples (TileSamples) and their values, into the film's image (MakeImage).
    AFFRAY_CHECK_EQ(samples.size(), expected);
    AFFRAY_CHECK_EQ(values.size(), expected);
    const size_t pixels = static_cast<size_t>(m_xres) * m_yres;
    AFFRAY_CHECK_EQ(image->width, m_xres);
    AFFRAY_CHECK_EQ(image->height, m_yres);
    AFFRAY_CHECK_EQ(image->rgba.size(), pixels * 4);
    const ChannelPointers ch = FindChannels(image);
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x)
            WritePixel(*this, Gather(*this, x, y, region, samples, values), static_cast<size_t>(y) * m_xres + x, ch,
                       image);
}

bool PasteCrop(const image::ImageBuffer& crop, const PixelRange& range, image::ImageBuffer* whole, std::string* error) {
    const size_t pixels = static_cast<size_t>(crop.width) * crop.height;
    if (whole->width == 0 && whole->height == 0) {
        *whole = image::ImageBuffer{crop.width, crop.height, std::vector<float>(pixels * 4, 0.0f), {}, {}};
    }
    if (whole->width != crop.width || whole->height != crop.height) {
        if (error)
            *error = "cannot paste a " + std::to_string(crop.width) + "x" + std::to_string(crop.height) +
                     " crop into a " + std::to_string(whole->width) + "x" + std::to_string(whole->height) + " image";
        return false;
    }
    for (const auto& [name, values] : crop.extraChannels)
        if (values.size() != pixels) {
            if (error)
                *error = "crop channel '" + name + "' holds " + std::to_string(values.size()) + " values, not " +
                         std::to_string(pixels);
            return false;
        }
    if (crop.rgba.size() != pixels * 4) {
        if (error)
            *error =
                "crop RGBA holds " + std::to_string(crop.rgba.size()) + " values, not " + std::to_string(pixels * 4);
        return false;
    }
    const PixelRange r{std::max(range.x0, 0), std::min(range.x1, crop.width), std::max(range.y0, 0),
                       std::min(range.y1, crop.height)};
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const size_t pixel = static_cast<size_t>(y) * crop.width + x;
            std::copy_n(&crop.rgba[pixel * 4], 4, &whole->rgba[pixel * 4]);
        }
    for (const auto& [name, values] : crop.extraChannels) {
        auto it = std::find_if(whole->extraChannels.begin(), whole->extraChannels.end(),
                               [&name = name](const auto& channel) { return channel.first == name; });
        if (it == whole->extraChannels.end()) {
            whole->extraChannels.emplace_back(name, std::vector<float>(pixels, 0.0f));
            it = std::prev(whole->extraChannels.end());
        }
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) {
                const size_t pixel = static_cast<size_t>(y) * crop.width + x;
                it->second[pixel] = values[pixel];
            }
    }
    return true;
}

}  // namespace affray::renderer
