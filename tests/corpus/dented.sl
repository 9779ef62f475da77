/*
 * dented.sl: the RenderMan Companion's dented metal: turbulence of |noise - 1/2| cubed, so only
 * its peaks dent the surface. Constructs: a loop with a multiplicative step, abs, the cube by
 * pow, transform to "shader", P -= with a normalized N.
 */
displacement dented(float Km = 0.6, frequency = 2)
{
    float size = 1, magnitude = 0, i;
    point P2 = transform("shader", P) * frequency;
    for (i = 0; i < 5; i += 1) {
        magnitude += abs(.5 - noise(P2 * size)) / size;
        size *= 2;
    }
    P2 = P - normalize(N) * (Km * pow(magnitude, 3));
    P = P2;
    N = calculatenormal(P);
}
