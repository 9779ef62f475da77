/*
 * wrinkles.sl: skin wrinkles: noise stretched along one direction so its creases run lengthwise,
 * sharpened by abs and pow. Constructs: a point built from scaled components, abs, pow, a
 * 2-argument noise, transform to "shader".
 */
#include "patterns.h"

displacement wrinkles(float Km = 0.02, frequency = 8, stretch = 6, sharpness = 3)
{
    point PP = transform("shader", P);
    float x = xcomp(PP) * frequency, y = ycomp(PP) * frequency / stretch;
    float crease = 1 - abs(snoisexy(x, y));
    crease = pow(crease, sharpness);
    float fine = 0.3 * abs(snoise(PP * frequency * 3));
    P -= Km * (crease + fine) * normalize(N);
    N = calculatenormal(P);
}
