/*
 * cobblestones.sl: a cobbled street: each Worley cell a stone, domed by F2 - F1 (the distance to
 * the nearest border) and raised by its own cellnoise height. Constructs: the header's voronoi2d,
 * sqrt of a clamped value, smoothstep, min.
 */
#include "patterns.h"

displacement cobblestones(float Km = 0.03, frequency = 7, jitter = 0.9, mortar = 0.05)
{
    float f1, f2, id;
    voronoi2d(s * frequency, t * frequency, jitter, f1, f2, id);
    float border = f2 - f1;
    float dome = sqrt(clamp(border, 0, 1)) * smoothstep(0, mortar, border);
    P += Km * min(dome * (0.7 + 0.3 * id), 1) * normalize(N);
    N = calculatenormal(P);
}
