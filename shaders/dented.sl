/*
 * dented.sl: the classic "dented" metal: fBm noise pushed inwards only, so the surface looks
 * hammered. Exercises #include, a user function with a loop whose trip count is a parameter,
 * transform to shader space, pow and abs.
 *
 *   Km          depth of the dents
 *   frequency   dents per unit of shader space
 *   octaves     noise octaves summed
 *   sharpness   exponent shaping the dents (1: soft, larger: sharper)
 */
#include "noises.h"

displacement dented(float Km = 0.05, frequency = 3, octaves = 4, sharpness = 2)
{
    point Pshad = transform("shader", P) * frequency;
    float magnitude = pow(abs(fbm(Pshad, octaves, 2, 0.5)), sharpness);
    P -= Km * magnitude * normalize(N);
    N = calculatenormal(P);
}
