/*
 * gerstner.sl: an ocean of directional swells, a sum over a table of wave directions and
 * lengths. Constructs: uniform float arrays with initialisers, indexing in a loop, cos, sin,
 * radians, a dot product of vectors.
 */
displacement gerstner(float Km = 0.015, scale = 1)
{
    uniform float angles[4] = {0, 40, 75, 130};
    uniform float lengths[4] = {0.3, 0.17, 0.11, 0.07};
    uniform float amps[4] = {1, 0.6, 0.4, 0.25};
    point PP = transform("shader", P) * scale;
    float h = 0, i;
    for (i = 0; i < 4; i += 1) {
        vector dir = vector(cos(radians(angles[i])), sin(radians(angles[i])), 0);
        float x = vector(PP) . dir;
        h += amps[i] * sin(2 * PI * x / lengths[i]);
    }
    P += Km * h * normalize(N);
    N = calculatenormal(P);
}
