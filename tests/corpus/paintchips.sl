/*
 * paintchips.sl: chipped paint: where fBm falls below a threshold the paint layer is gone, with a
 * sharp edge. Constructs: the header's fBm and boxstep, a uniform parameter in a varying test,
 * if/else, the Companion's P - Km * N * ... ordering.
 */
#include "patterns.h"

displacement paintchips(float Km = 0.01, frequency = 4, threshold = -0.1, edge = 0.05)
{
    point PP = transform("shader", P) * frequency;
    float f = fBm(PP, 4, 2, 0.5);
    float paint;
    if (f < threshold)
        paint = 0;
    else
        paint = boxstep(threshold, threshold + edge, f);
    P = P - Km * normalize(N) * (1 - paint);
    N = calculatenormal(P);
}
