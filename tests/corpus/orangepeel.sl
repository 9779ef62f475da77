/*
 * orangepeel.sl: orange-peel paint: fine noise that moves P along a noise vector as well as the
 * normal. Constructs: vector noise, the header's vsnoise, vtransform from "shader" space,
 * P += of a vector.
 */
#include "patterns.h"

displacement orangepeel(float Km = 0.004, frequency = 30, sideways = 0.3)
{
    point PP = transform("shader", P) * frequency;
    vector wobble = vtransform("shader", "current", vsnoise(PP));
    float bump = snoise(PP);
    P += Km * (bump * normalize(N) + sideways * wobble);
    N = calculatenormal(P);
}
