/*
 * mudcracks.sl: dried mud: Worley cells as plates, cracks where F2 - F1 is small, plates curling
 * up at their edges. Constructs: the header's voronoi2d, 1 - smoothstep, mix, a product of
 * profiles.
 */
#include "patterns.h"

displacement mudcracks(float Km = 0.03, frequency = 5, crackwidth = 0.15, curl = 0.4)
{
    float f1, f2, id;
    voronoi2d(s * frequency, t * frequency, 1, f1, f2, id);
    float border = f2 - f1;
    float crack = 1 - smoothstep(0, crackwidth, border);
    float lip = curl * (1 - smoothstep(crackwidth, 4 * crackwidth, border));
    float h = mix(1 + lip, 0, crack);
    P += Km * (h - 1) * normalize(N);
    N = calculatenormal(P);
}
