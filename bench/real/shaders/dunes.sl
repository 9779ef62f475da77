/*
 * dunes.sl: weathering for a terrain of separate patches (bench/real/heightfield.rib): three
 * octaves of noise in shader space plus small sharp bumps (the square of a high octave), added
 * as height straight up the shader space's z axis, the way a height field is weathered. The
 * offset is a function of P alone, so the patches, which share their corners and edges, stay
 * closed across their seams whatever their normals do there.
 *
 *   Km          height of the noise, in shader units
 *   frequency   noise features per shader unit
 *   Kbump       height of the fine bumps
 */
displacement dunes(float Km = 0.5, frequency = 0.25, Kbump = 0.1)
{
    point Ps = transform("shader", P) * frequency;
    float h = 0, amp = 1, f = 1;
    float i;
    for (i = 0; i < 3; i += 1) {
        h += amp * (noise(Ps * f) - 0.5);
        amp *= 0.5;
        f *= 2.17;
    }
    float b = max(noise(Ps * 9.3) - 0.3, 0);
    P += vector "shader" (0, 0, 1) * (Km * h + Kbump * 4 * b * b);
    N = calculatenormal(P);
}
