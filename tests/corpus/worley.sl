/*
 * worley.sl: Worley's F1 cellular texture as raised scales. Constructs: the header's voronoi2d
 * (nested loops over neighbouring cells, cellnoise of two floats, output parameters), s and t.
 */
#include "patterns.h"

displacement worley(float Km = 0.03, frequency = 6, jitter = 0.8)
{
    float f1, f2, id;
    voronoi2d(s * frequency, t * frequency, jitter, f1, f2, id);
    P += Km * (0.7 - f1) * normalize(N);
    N = calculatenormal(P);
}
