/*
 * dunes.sl: wind-blown sand dunes: asymmetric ridges (a gentle windward slope, a steep lee) whose
 * crest lines wander with noise. Constructs: mod, a piecewise profile with if/else, smoothstep,
 * 2-D noise.
 */
#include "patterns.h"

displacement dunes(float Km = 0.05, frequency = 5, wander = 0.4, lee = 0.2)
{
    float x = s * frequency + wander * snoisexy(t * 3, s * 2);
    float f = mod(x, 1);
    float h;
    if (f < 1 - lee)
        h = smoothstep(0, 1 - lee, f);
    else
        h = 1 - smoothstep(1 - lee, 1, f);
    P += Km * h * normalize(N);
    N = calculatenormal(P);
}
