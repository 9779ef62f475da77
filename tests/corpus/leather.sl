/*
 * leather.sl: grained leather: Worley cells of a noise-warped domain with soft creases between
 * them and pores from fine noise. Constructs: the header's voronoi2d and snoisexy, max, min,
 * pow.
 */
#include "patterns.h"

displacement leather(float Km = 0.01, frequency = 12, warp = 0.3, poreDepth = 0.3)
{
    float ss = s * frequency + warp * snoisexy(s * 4, t * 4);
    float tt = t * frequency + warp * snoisexy(s * 4 + 7, t * 4 + 3);
    float f1, f2, id;
    voronoi2d(ss, tt, 0.9, f1, f2, id);
    float crease = min(1, pow(max(f2 - f1, 0) * 3, 0.5));
    float pore = poreDepth * max(0, snoisexy(s * 90, t * 90) - 0.6);
    P += Km * (crease - pore) * normalize(N);
    N = calculatenormal(P);
}
