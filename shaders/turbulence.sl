/*
 * turbulence.sl: dents in the style of the classic "dented" shader of the RenderMan Companion:
 * turbulence, |noise - 1/2| summed over octaves of doubling frequency and halving weight, cubed so
 * that only its peaks bite, pushes the surface in along N.
 *
 *   Km         depth of the dents
 *   frequency  of the first octave, in shader space
 *   octaves    octaves summed (six in the classic shader)
 */
displacement turbulence(float Km = 0.5, frequency = 1.5, octaves = 6)
{
    point Q = transform("shader", P) * frequency;
    float size = 1, magnitude = 0, i;
    for (i = 0; i < octaves; i += 1) {
        magnitude += abs(0.5 - noise(Q * size)) / size;
        size *= 2;
    }
    P -= Km * magnitude * magnitude * magnitude * normalize(N);
    N = calculatenormal(P);
}
