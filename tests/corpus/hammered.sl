/*
 * hammered.sl: hammered copper: each Worley cell is a shallow cup, F1 squared (bubbly's
 * paraboloids upside down). Constructs: the header's voronoi2d, squaring, cellnoise ids scaling
 * each cup.
 */
#include "patterns.h"

displacement hammered(float Km = 0.015, frequency = 8, jitter = 1)
{
    float f1, f2, id;
    voronoi2d(s * frequency, t * frequency, jitter, f1, f2, id);
    float cup = f1 * f1 * (0.6 + 0.8 * id);
    P += Km * cup * normalize(N);
    N = calculatenormal(P);
}
