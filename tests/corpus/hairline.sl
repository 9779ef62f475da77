/*
 * hairline.sl: wind-combed fur stubble: a direction bent a few times towards a noise field and
 * renormalised each time, the displacement its component along the normal. Constructs: a loop
 * that normalizes a vector it keeps updating, vector noise, the dot product.
 */
#include "patterns.h"

displacement hairline(float Km = 0.01, frequency = 20, bend = 0.6, steps = 3)
{
    normal Nn = normalize(N);
    point PP = transform("shader", P) * frequency;
    vector dir = vector(Nn);
    float i;
    for (i = 0; i < steps; i += 1) {
        dir = normalize(dir + bend * vsnoise(PP + i * vector(1.7, 9.2, 3.3)));
    }
    P += Km * (dir . Nn) * Nn;
    N = calculatenormal(P);
}
