/*
 * lumpy.sl: soft lumps of fBm in shader space, displaced along the normal, the kind of shader
 * Advanced RenderMan opens with. Style: Gritz. Constructs: #include, transform to "shader",
 * a user function with a loop over uniform octaves, normalize, calculatenormal.
 */
#include "patterns.h"

displacement lumpy(float Km = 0.04, frequency = 2, maxoctaves = 4;
                   string shadingspace = "shader")
{
    point PP = transform(shadingspace, P) * frequency;
    float lumps = fBm(PP, maxoctaves, 2, 0.5);
    normal Nn = normalize(N);
    P += Km * lumps * Nn;
    N = calculatenormal(P);
}
