// texture/texture.h: texture maps for displacement, read through OpenImageIO (image_io.h) and bounded by
// min/max pyramids (issue 16). The stage sits beside the number types: it knows doubles and
// closed ranges only; vm/texture_lookup.h turns these into the lookups of every number
// type the VM runs.
//
// Semantics (double is the reference, as everywhere in affray):
//  - A map is width x height texels of `channels` floats, from MIP level 0 of subimage 0 of the
//    file. Texel (x, y) covers [x, x+1) x [y, y+1) in texel space; its centre is at (x + 0.5,
//    y + 0.5). Texture coordinates (s, t) in [0, 1]^2 cover the image: x = s * width,
//    y = t * height, t = 0 the first (top) row, as RenderMan's texture() reads a map.
//    Texels that are NaN or infinite in the file are read as 0 (a warning says how many), so
//    every lookup of a finite coordinate is finite.
//  - Outside [0, width) x [0, height) the wrap mode of each axis applies to texel indices:
//    Black (a texel outside is 0), Clamp (the nearest edge texel), Periodic (index modulo the
//    size).
//  - Bilinear lookup (every filter with blur 0 but CatmullRom): with fx = s*width - 0.5,
//    x0 = floor(fx), a = fx - x0 (likewise y0, b), the value is
//        (1-b) * ((1-a) T(x0,y0) + a T(x0+1,y0)) + b * ((1-a) T(x0,y0+1) + a T(x0+1,y0+1)),
//    every product and sum in double, in that order.
//  - CatmullRom: the bicubic Catmull-Rom spline over the 4x4 texels around (fx, fy), same layout.
//  - Blur (LookupOptions::sblur, tblur, fractions of the image's width and height): the value is
//    the weighted average of the filter's taps (bilinear or Catmull-Rom lookups) over a grid of
//    n x n points, n = kBlurTaps, spread across [s - sblur/2, s + sblur/2] x [t - tblur/2,
//    t + tblur/2]; weights: Box equal, Triangle 1 - |offset|/(half width) (tent), Gaussian
//    exp(-8 (offset/width)^2) per axis; normalised to sum 1.
//  - Four-corner lookup (RSL's texture(name, s1,t1, s2,t2, s3,t3, s4,t4)): the mean of the
//    lookups at a kQuadTaps x kQuadTaps grid over the bilinear quadrilateral of the corners
//    (corner order 1, 2 along s, then 3, 4), each lookup blurred as above.
//  - Coordinates that are not finite, or farther than kMaxTexelCoordinate texels from the image,
//    give the fill value; so does a channel the map does not have, and every lookup of a map that
//    could not be read (TextureSlot with no map, a "fill" given).
//
// Bounds (RangeOver): every filter above but CatmullRom has non-negative weights summing to 1,
// so its value lies between the least and the greatest texel it reads; those texels lie in the
// integer rectangle covering [slo*w - sblur*w/2 - 0.5, shi*w + sblur*w/2 + 0.5] (likewise y),
// taken through the wrap mode. Catmull-Rom's weights have negative lobes: per axis the negative
// weights sum to f(1-f)/2 <= 1/8, so over the tensor product they sum to at most
// 1/8 + 1/8 + 2/64 = 9/32; with texels in [m, M] the value lies in
// [m - 9/32 (M - m), M + 9/32 (M - m)]. The double evaluation's rounding is covered by a relative
// slack of 2^-40 of the magnitude. The min/max pyramid makes a rectangle's range cost a few reads
// at any size.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace affray::texture {

enum class Wrap : uint8_t { Black, Clamp, Periodic };
enum class Filter : uint8_t { Box, Triangle, Gaussian, CatmullRom };

/// Parses "black", "clamp", "periodic" (also "repeat", OIIO's word) and "box", "triangle",
/// "gaussian", "catmull-rom" (also "catrom", "bicubic"); false if unknown.
bool ParseWrap(const std::string& name, Wrap* wrap);
bool ParseFilter(const std::string& name, Filter* filter);
const char* WrapName(Wrap w);
const char* FilterName(Filter f);

inline constexpr int kBlurTaps = 4;                             // per axis, where a blur is given
inline constexpr int kQuadTaps = 4;                             // per axis of a four-corner lookup
inline constexpr double kMaxTexelCoordinate = 1099511627776.0;  // 2^40

/// A closed range [lo, hi] of doubles; lo > hi never happens.
struct Range {
    double lo = 0, hi = 0;
};

/// One texture map in memory: its header, its min/max pyramid (always resident, about 1/6 of a
/// float per texel and channel), and its texels, resident in tiles read from the file on demand
/// within the process-wide memory budget (SetTileMemoryBudget), or all resident for a map made
/// from pixels. Immutable once made; every member is safe to call from many threads.
class TextureMap {
  public:
    /// A map of the given texels (row-major, channels interleaved, width*height*channels
    /// floats), for tests and generated maps. Non-finite texels become 0.
    static std::shared_ptr<const TextureMap> FromPixels(int width, int height, int channels, std::vector<float> texels,
                                                        Wrap swrap = Wrap::Periodic, Wrap twrap = Wrap::Periodic,
                                                        std::string name = "<pixels>");
    virtual ~TextureMap();

    int width() const { return m_width; }
    int height() const { return m_height; }
    int channels() const { return m_channels; }
    const std::string& name() const { return m_name; }
    /// The file's wrap modes (its "wrapmodes" attribute), Periodic where it names none.
    Wrap swrap() const { return m_swrap; }
    Wrap twrap() const { return m_twrap; }
    /// Texels that were NaN or infinite in the file (read as 0).
    int64_t nonFiniteTexels() const { return m_nonFinite; }

    /// Texel (x, y) of channel c, for 0 <= x < width, 0 <= y < height, 0 <= c < channels.
    float Texel(int x, int y, int c) const;
    /// The least and greatest texel of channel c over the integer rectangle [x0, x1] x [y0, y1]
    /// (x0 <= x1, y0 <= y1, any integers: indices outside the image go through the wrap modes).
    Range RangeOfTexels(int64_t x0, int64_t x1, int64_t y0, int64_t y1, int c, Wrap swrap, Wrap twrap) const;
    /// Bytes held now: the pyramid and the resident tiles.
    size_t residentBytes() const;

  protected:
    TextureMap() = default;
    int m_width = 0, m_height = 0, m_channels = 0;
    std::string m_name;
    Wrap m_swrap = Wrap::Periodic, m_twrap = Wrap::Periodic;
    int64_t m_nonFinite = 0;
};

/// The options of one lookup call site, fixed when the shader is compiled.
struct LookupOptions {
    int channel = 0;  // the first channel read
    Wrap swrap = Wrap::Periodic, twrap = Wrap::Periodic;
    Filter filter = Filter::Box;
    double sblur = 0, tblur = 0;  // fractions of the image's width and height
    double fill = 0;              // outside, missing channels, missing map
};

/// The lookup at (s, t) of channel `options.channel` (+ `offset`, for the channels of a color);
/// `map` may be null (the fill value).
double Sample(const TextureMap* map, const LookupOptions& options, int offset, double s, double t);
/// The four-corner lookup; s and t hold the corners 1..4.
double SampleQuad(const TextureMap* map, const LookupOptions& options, int offset, const double s[4],
                  const double t[4]);
/// Sample and its partial derivatives in s and t at the point (one-sided where the lookup has a
/// kink: the side of the greater coordinate). Zero derivatives where the value is the fill.
double SampleGrad(const TextureMap* map, const LookupOptions& options, int offset, double s, double t, double* dds,
                  double* ddt);

/// SampleQuad, bit for bit, and its partial derivatives in each corner's s and t (dS[i], dT[i]):
/// the mean of the taps' SampleGrad times each corner's bilinear weight at the tap.
double SampleQuadGrad(const TextureMap* map, const LookupOptions& options, int offset, const double s[4],
                      const double t[4], double dS[4], double dT[4]);

/// A range containing Sample(map, options, offset, s, t) for every double s in [s.lo, s.hi] and
/// t in [t.lo, t.hi] (infinite ends allowed: the fill value is then in the range too).
Range RangeOver(const TextureMap* map, const LookupOptions& options, int offset, Range s, Range t);
/// The same for SampleQuad over corner ranges s[i], t[i].
Range RangeOverQuad(const TextureMap* map, const LookupOptions& options, int offset, const Range s[4],
                    const Range t[4]);
/// Bounds on |d Sample / ds| and |d Sample / dt| over the region (infinite if the region is not
/// finite); written to *sSlope and *tSlope.
void SlopeOver(const TextureMap* map, const LookupOptions& options, int offset, Range s, Range t, double* sSlope,
               double* tSlope);

/// RenderMan's MakeTexture: writes `picture` (any image OpenImageIO reads) to `output` as a tiled,
/// mip-mapped texture (maketx's TIFF) with the wrap modes in its "wrapmodes". False with *error
/// set (one line) if the picture cannot be read or the output written; nothing is left behind.
bool MakeTexture(const std::string& picture, const std::string& output, Wrap swrap, Wrap twrap, std::string* error);

/// The process-wide cache of maps read from files. Open returns the map of `path` (read once per
/// file and modification time: a file changed on disk is read again), or null with *error set
/// (the file is missing, unreadable, or no image).
std::shared_ptr<const TextureMap> Open(const std::string& path, std::string* error);
/// The budget for texel tiles of every map read from a file (default 512 MiB): tiles are read
/// on demand and the least recently used are dropped beyond it.
void SetTileMemoryBudget(size_t bytes);
size_t TileMemoryBudget();
/// Statistics since the start of the process: tiles read from files and tiles dropped.
struct CacheStats {
    int64_t tilesRead = 0, tilesDropped = 0;
    size_t residentBytes = 0;
};
CacheStats Stats();

}  // namespace affray::texture
