/*
 * dturb.sl: turbulence displacement with its octaves cut off at the sampling rate and the last
 * one faded in (K-3D's dturb style). Constructs: filterwidthp (area, sqrt, max), clamp, a loop
 * whose bound depends on the filter width, pow to flatten valleys.
 */
#include "patterns.h"

displacement dturb(float Km = 0.05, freq = 4, flatness = 1.5, maxfreq = 4)
{
    float f, turb, fade;
    point PP = transform("shader", P) * freq;
    float width = filterwidthp(PP);
    float cutoff = clamp(0.5 / width, 0, maxfreq);
    turb = 0;
    for (f = 1; f < 0.5 * cutoff && f < maxfreq; f *= 2)
        turb += abs(snoise(PP * f)) / f;
    fade = clamp(2 * (cutoff - f) / cutoff, 0, 1);
    turb += fade * abs(snoise(PP * f)) / f;
    P += Km * pow(turb, flatness) * normalize(N);
    N = calculatenormal(P);
}
