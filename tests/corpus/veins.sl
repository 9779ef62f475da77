/*
 * veins.sl: raised marble veins: a sine of one coordinate warped by turbulence, sharpened where
 * it crosses zero. Constructs: the header's turbulence, sin, abs, pow, smoothstep, a vector
 * noise warp of the point.
 */
#include "patterns.h"

displacement veins(float Km = 0.02, frequency = 3, veinfreq = 4, warp = 0.6, sharpness = 12)
{
    point PP = transform("shader", P) * frequency;
    PP += warp * vsnoise(PP * 0.5);
    float turb = turbulence(PP, 4, 2, 0.5);
    float vein = abs(sin(veinfreq * (xcomp(PP) + 2 * turb)));
    vein = pow(1 - vein, sharpness);
    P += Km * smoothstep(0.05, 0.6, vein) * normalize(N);
    N = calculatenormal(P);
}
