/*
 * castucco.sl: Californian stucco: fBm thresholded into flat mesas and rounded troughs.
 * Constructs: the header's fBm, smoothstep between two parameters, a uniform string compare to
 * pick the space.
 */
#include "patterns.h"

displacement castucco(float freq = 2, Km = 0.04, octaves = 3, trough = -0.15, peak = 0.25;
                      string space = "shader")
{
    point Pshad;
    if (space == "object")
        Pshad = transform("object", P) * freq;
    else
        Pshad = transform("shader", P) * freq;
    float f = fBm(Pshad, octaves, 2, 0.6);
    float mesa = smoothstep(trough, peak, f);
    P += Km * mesa * normalize(N);
    N = calculatenormal(P);
}
