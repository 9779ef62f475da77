/*
 * erosion.sl: eroded terrain: an fBm heightfield whose valleys are flattened by a power and whose
 * slopes are cut into terraces. Constructs: the header's fBm, pow of a clamped value, floor,
 * smoothstep within a terrace, mix.
 */
#include "patterns.h"

displacement erosion(float Km = 0.08, frequency = 1.5, octaves = 5, flatten = 2, terraces = 6,
                     terraceSharpness = 0.7)
{
    point PP = transform("shader", P) * frequency;
    float h = clamp(0.5 + 0.5 * fBm(PP, octaves, 2, 0.5), 0, 1);
    h = pow(h, flatten);
    float level = floor(h * terraces);
    float within = h * terraces - level;
    float stepped = (level + smoothstep(terraceSharpness, 1, within)) / terraces;
    h = mix(h, stepped, 0.8);
    P += Km * h * normalize(N);
    N = calculatenormal(P);
}
