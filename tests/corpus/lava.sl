/*
 * lava.sl: ropey pahoehoe lava: turbulence of a domain warped twice by vector noise.
 * Constructs: vector noise of a point, the header's vsnoise and turbulence, chained warps.
 */
#include "patterns.h"

displacement lava(float Km = 0.04, frequency = 3, warp = 0.7)
{
    point PP = transform("shader", P) * frequency;
    vector w1 = vsnoise(PP);
    vector w2 = vsnoise(PP + warp * w1 + vector(5.2, 1.3, 2.8));
    float h = turbulence(PP + warp * w2, 3, 2, 0.5);
    P += Km * h * normalize(N);
    N = calculatenormal(P);
}
