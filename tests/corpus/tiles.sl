/*
 * tiles.sl: square ceramic tiles with rounded shoulders and a slight random tilt per tile.
 * Constructs: the header's whichtile and repeat, smoothstep shoulders, cellnoise per tile,
 * a uniform if on a parameter.
 */
#include "patterns.h"

displacement tiles(float Km = 0.02, tilesPerUnit = 5, groove = 0.06, shoulder = 0.08, tilt = 0.3)
{
    float ts = whichtile(s, tilesPerUnit), tt = whichtile(t, tilesPerUnit);
    float fs = repeat(s, tilesPerUnit), ft = repeat(t, tilesPerUnit);
    float edge = min(min(fs, 1 - fs), min(ft, 1 - ft));
    float height = smoothstep(groove, groove + shoulder, edge);
    if (tilt > 0)
        height += tilt * (float cellnoise(ts, tt) - 0.5) * (fs - 0.5) * height;
    P += Km * (height - 1) * normalize(N);
    N = calculatenormal(P);
}
