/*
 * woodgrain.sl: raised late-wood rings of a plank cut along the trunk: the distance from the trunk
 * axis, wobbled by noise, taken modulo the ring spacing. Constructs: transform to "shader", xcomp
 * and zcomp, sqrt, the header's snoise, mod, smoothstep.
 */
#include "patterns.h"

displacement woodgrain(float Km = 0.006, ringscale = 12, wobble = 0.05, grain = 3)
{
    point PP = transform("shader", P);
    point Q = PP + wobble * vector(snoise(PP * grain), snoise(PP * grain + vector(3.1, 1.7, 0)), 0);
    float r = sqrt(xcomp(Q) * xcomp(Q) + (zcomp(Q) + 0.7) * (zcomp(Q) + 0.7)) * ringscale;
    float ring = mod(r, 1);
    float late = smoothstep(0.6, 0.75, ring) - smoothstep(0.85, 1, ring);
    P += Km * late * normalize(N);
    N = calculatenormal(P);
}
