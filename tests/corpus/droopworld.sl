/*
 * droopworld.sl: melting wax: points slump along world -z by an amount that grows with noise and
 * with height, while the surface swells along its normal. Constructs: vtransform from "world",
 * a vector cast with a space, transform to "world", zcomp, clamp, the header's snoise.
 */
#include "patterns.h"

displacement droopworld(float Km = 0.03, slump = 0.05, frequency = 4)
{
    point Pw = transform("world", P);
    vector down = vtransform("world", "current", vector "world" (0, 0, -1));
    float n = 0.5 + 0.5 * snoise(Pw * frequency);
    float amount = slump * n * clamp(zcomp(Pw) + 1, 0, 2);
    P += amount * down + Km * n * normalize(N);
    N = calculatenormal(P);
}
