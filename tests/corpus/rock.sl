/*
 * rock.sl: weathered rock: fBm for the mass and a ridged multifractal for the strata, mixed by a
 * noise mask, the amount also written to an output parameter for a surface shader to read.
 * Constructs: the header's fBm and ridgedmf, an #ifdef renderer switch and an #if 0 block hiding
 * code that would not compile, an output varying shader parameter, mix.
 */
#include "patterns.h"

displacement rock(float Km = 0.05, frequency = 2; output varying float rockHeight = 0)
{
    point PP = transform("shader", P) * frequency;
#ifdef BMRT
    float mass = fBm(PP, 6, 2, 0.5);
#else
    float mass = fBm(PP, 3, 2, 0.5);
#endif
#if 0
    float strata = texture("strata.tx", s, t);  /* never compiled */
#endif
    float strata = ridgedmf(PP * vector(0.3, 0.3, 3), 3, 2, 1, 1, 2);
    float mask = smoothstep(0.3, 0.7, float noise(PP * 0.5));
    rockHeight = mix(mass, 0.5 * strata, mask);
    P += Km * rockHeight * normalize(N);
    N = calculatenormal(P);
}
