// texture/lookup_quad.cpp: the derivatives of the four-corner lookup (SampleQuadGrad), which the
// dual numbers take through the chain rule (vm/texture_lookup.h). Written on the public lookups:
// the taps are SampleQuad's (detail::ForEachQuadTap), in its order, and SampleGrad's value is
// Sample's bit for bit, so the value is SampleQuad's (tests/vm/conformance_test.cpp checks it on every draw).
#include "texture/texture.h"
#include "texture/texture_impl.h"

namespace affray::texture {

double SampleQuadGrad(const TextureMap* map, const LookupOptions& options, int offset, const double s[4],
                      const double t[4], double dS[4], double dT[4]) {
    for (int i = 0; i < 4; ++i) dS[i] = dT[i] = 0;
    const int64_t channel = static_cast<int64_t>(options.channel) + offset;
    if (!map || channel < 0 || channel >= map->channels()) return options.fill;
    constexpr double kTaps = kQuadTaps * kQuadTaps;
    double sum = 0;
    detail::ForEachQuadTap(s, t, [&](double ps, double pt, const double* w) {
        double gs = 0, gt = 0;
        sum += SampleGrad(map, options, offset, ps, pt, &gs, &gt);
        // The tap moves with corner k by its bilinear weight.
        for (int k = 0; k < 4; ++k) {
            dS[k] += w[k] * gs / kTaps;
            dT[k] += w[k] * gt / kTaps;
        }
    });
    return sum / kTaps;
}

}  // namespace affray::texture
