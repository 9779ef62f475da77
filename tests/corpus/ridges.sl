/*
 * ridges.sl: mountain ridges from Musgrave's ridged multifractal. Constructs: the header's
 * ridgedmf (pow of uniform values, clamp, weights carried across octaves).
 */
#include "patterns.h"

displacement ridges(float Km = 0.05, frequency = 2, octaves = 5, lacunarity = 2.1, H = 1, offset = 1,
                    gain = 2)
{
    point PP = transform("shader", P) * frequency;
    float h = ridgedmf(PP, octaves, lacunarity, H, offset, gain);
    P += Km * (h - 0.5) * normalize(N);
    N = calculatenormal(P);
}
