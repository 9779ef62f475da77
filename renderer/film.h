// renderer/film.h: from camera samples to pixels: the crop window, stratified sample positions,
// the reconstruction filter (RI Spec 3.2 appendix E), exposure and the AOV channels.
//
// How a renderer uses it (one Film per image, shared read-only by all threads):
//   Film film(scene.camera, channels);               // channels from ParseDisplayMode(displayMode)
//   image::ImageBuffer image = film.MakeImage();     // full resolution, zero outside the crop
//   for each tile in film.Tiles(32), on any thread, in any order:
//       film.TileSamples(tile, &samples);            // the tile's pixels grown by the filter margin
//       values[i] = trace and shade samples[i].raster, for every i
//       film.ResolveTile(tile, samples, values, &image);  // writes only the tile's pixels
//
// Why the result does not depend on tiling or threads, bit for bit: a sample's position is a
// hash of (pixel, sample index, seed), not of any order of work, and each pixel is summed over
// the samples of its filter footprint in one fixed order (footprint pixels row by row, then
// sample index), which is the same whichever tile the pixel lies in. The price: samples in a
// tile's margin are traced again by the neighbouring tile (about 4 * margin / tileSize extra).
//
// Raster space: x right, y down, pixel (x, y) covers [x, x+1) x [y, y+1), its centre at
// (x + 0.5, y + 0.5) -- Camera::GenerateRay's convention.
//
// Output channels (EXR names, layer.component so OpenImageIO and Nuke group them):
//   R G B A                RGBA, always; filtered (weighted mean), exposure applied to RGB.
//   Z                      camera-space depth of the hit; kNoHitDepth for a miss.
//   N.X N.Y N.Z            world-space shading normal (0 for a miss).
//   P.X P.Y P.Z            world-space hit point (0 for a miss).
//   st.s st.t              the surface parameters (u, v) of the hit (0 for a miss).
//   cost                   regions bounded by the intersector, summed over the pixel's samples.
//   err                    certified geometric error of the hits, maximum over the pixel's samples.
// Depths, normals, points and parameters do not average meaningfully, so Z, N, P and st are not
// filtered: they come from the pixel's own sample nearest its centre (ties: lowest index).
// Pixels outside the crop window are 0 in every channel (alpha 0): a crop render is a full
// resolution image, so merging crops is pasting rectangles (PasteCrop).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "image/exr_writer.h"
#include "scene/display.h"
#include "scene/scene.h"

namespace affray::renderer {

/// The depth written for a sample that hits nothing: RenderMan's default far clipping plane.
/// Large but finite, so tools that take minima or differences of Z keep working.
constexpr double kNoHitDepth = 1e30;

/// A rectangle of pixels [x0, x1) x [y0, y1).
struct PixelRange {
    int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    bool Contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
    bool operator==(const PixelRange&) const = default;
};

/// "[x0,x1)x[y0,y1)", for logs and test messages.
std::string ToString(const PixelRange& range);

/// The pixels the camera's CropWindow covers, per RI Spec 3.2 (RiCropWindow):
/// x0 = clamp(ceil(xres * xmin - 0.5)), x1 = clamp(ceil(xres * xmax - 0.5)), the same in y,
/// clamped to the image. Crops whose windows partition [0,1]^2 partition the pixels exactly.
PixelRange CropPixels(const CameraDesc& camera);

/// The names Film::MakeImage gives the channels beyond RGBA, in file order.
std::vector<std::string> ChannelNames(const DisplayChannels& channels);

/// One camera sample: the pixel it belongs to, its index there, and its raster position.
struct Sample {
    int px = 0, py = 0;  ///< The pixel whose stratum holds the sample.
    int index = 0;       ///< 0 .. xsamples * ysamples - 1, row by row over the strata.
    glm::dvec2 raster{0.0};
    /// Its point of the lens, in [0, 1]^2 (Camera::GenerateRay; unused by a pinhole camera).
    glm::dvec2 lens{0.5};
    /// Its time, as a fraction of the shutter's interval in [0, 1) (Film::TimePosition; 0 when
    /// the shutter does not open).
    double time = 0;
};

/// What the renderer found for one sample.
struct SampleValue {
    glm::dvec3 rgb{0.0};
    double alpha = 0;  ///< 1 for a hit, 0 for a miss.
    double z = kNoHitDepth;
    glm::dvec3 N{0.0}, P{0.0};
    glm::dvec2 st{0.0};
    std::int64_t cost = 0;  ///< Regions the intersector bounded for this sample's camera ray.
    double err = 0;         ///< The hit's certified geometric error (0 for a miss).
};

class Film {
  public:
    /// Sampling rates below 1 are taken as 1 (RI Spec), filter widths below 1 pixel as 1 (so every
    /// pixel's own samples lie in its footprint and no pixel is left without weight).
    explicit Film(const CameraDesc& camera, const DisplayChannels& channels = {}, std::uint64_t seed = 0);

    PixelRange crop() const { return m_crop; }
    int xres() const { return m_xres; }
    int yres() const { return m_yres; }
    /// Pixels a sample may lie away from a pixel it contributes to, in x and in y.
    int marginX() const { return m_marginX; }
    int marginY() const { return m_marginY; }
    int samplesPerPixel() const { return m_xsamples * m_ysamples; }

    /// Tiles of at most tileSize x tileSize pixels covering the crop, row by row from its corner.
    std::vector<PixelRange> Tiles(int tileSize) const;

    /// The pixels whose samples a tile needs: the tile grown by the margins, clipped to the image
    /// (not to the crop, so a crop render filters exactly as the whole render does).
    PixelRange SampleRegion(const PixelRange& tile) const;

    /// The raster position of sample `index` of pixel (px, py): jittered within its stratum by
    /// a hash of (px, py, index, seed), so it is the same whoever asks and when; at the stratum's
    /// centre if the camera's jitter is off.
    glm::dvec2 SamplePosition(int px, int py, int index) const;

    /// The lens position of sample `index` of pixel (px, py), in [0, 1]^2: the pixel's samples
    /// take the strata of an xsamples x ysamples grid over the lens one each, in an order
    /// shuffled per pixel (so that a sample's lens stratum does not follow its place in the
    /// pixel), jittered within them as SamplePosition is (centred without jitter).
    glm::dvec2 LensPosition(int px, int py, int index) const;
    /// The time of sample `index` of pixel (px, py), as a fraction of the shutter's interval in
    /// [0, 1): the pixel's samples take the strata of [0, 1) cut in xsamples * ysamples one each,
    /// in an order shuffled per pixel apart from the lens's (so that time and lens position are
    /// not tied), jittered as the positions are.
    double TimePosition(int px, int py, int index) const;

    /// Every sample of SampleRegion(tile), row by row over its pixels, then by index; with a
    /// lens (LensP), each with its LensPosition.
    void TileSamples(const PixelRange& tile, std::vector<Sample>* out) const;

    /// The filter weight of a sample at offset (dx, dy) from a pixel centre, or 0 if the offset
    /// is outside the footprint [-xwidth/2, xwidth/2) x [-ywidth/2, ywidth/2) (half open, so a
    /// box of width 1 gives each sample to exactly one pixel). Box: 1. Gaussian, RI appendix E:
    /// exp(-2 (x'^2 + y'^2)) with x' = dx / (xwidth/2), y' = dy / (ywidth/2): exp(-2) at the edge.
    double FilterWeight(double dx, double dy) const;

    /// A full-resolution image, all zero, with the extra channels `channels` asks for.
    image::ImageBuffer MakeImage() const;

    /// Filters the tile's pixels from `samples` (as TileSamples(tile) gave them) and `values`
    /// (one per sample) into `image` (from MakeImage), applying exposure. Writes only the tile's
    /// pixels, so threads may resolve disjoint tiles into one image concurrently. Channels the
    /// image lacks are skipped.
    void ResolveTile(const PixelRange& tile, const std::vector<Sample>& samples, const std::vector<SampleValue>& values,
                     image::ImageBuffer* image) const;

    /// RI Exposure: (gain * c)^(1/gamma) per component; negative components become 0 unless
    /// gamma is 1 (a power of a negative number is undefined).
    double Expose(double c) const;
    /// Imager "background": the colour composited under each pixel before the exposure, if any.
    const std::optional<glm::dvec3>& Background() const { return m_background; }

  private:
    int m_xres, m_yres;
    PixelRange m_crop;
    int m_xsamples, m_ysamples;
    bool m_jitter;
    FilterDesc m_filter;
    double m_halfX, m_halfY;  ///< Filter half-widths, pixels.
    int m_marginX, m_marginY;
    double m_gain, m_gamma;
    std::optional<glm::dvec3> m_background;
    DisplayChannels m_channels;
    std::uint64_t m_seed;
    bool m_lens;     ///< LensP: samples take lens positions
    bool m_shutter;  ///< ShutterOpenP: samples take times
};

/// The counter-based hash behind the sample jitter (splitmix64-style finaliser over the packed
/// key): a well-mixed 64-bit value for each (x, y, index, seed).
std::uint64_t SampleHash(int x, int y, int index, std::uint64_t seed);

/// Copies the pixels of `range` in every channel of `crop` into `whole` (same resolution). An
/// empty `whole` (width 0) becomes an all-zero image shaped like `crop` first; channels `whole`
/// lacks are added, zero. Returns false with *error set if the resolutions differ.
bool PasteCrop(const image::ImageBuffer& crop, const PixelRange& range, image::ImageBuffer* whole, std::string* error);

}  // namespace affray::renderer
