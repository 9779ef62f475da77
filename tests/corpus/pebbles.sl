/*
 * pebbles.sl: a beach of round pebbles: one jittered pebble per cell, each an ellipsoidal cap; the
 * highest cap over the neighbouring cells wins. Constructs: nested loops, vector cellnoise of a
 * point, max, sqrt of a positive part, comp().
 */
displacement pebbles(float Km = 0.03, frequency = 6, size = 0.45)
{
    point here = point(s * frequency, t * frequency, 0);
    float cs = floor(comp(here, 0)), ct = floor(comp(here, 1));
    float h = 0, i, j;
    for (i = -1; i <= 1; i += 1)
        for (j = -1; j <= 1; j += 1) {
            point cell = point(cs + i, ct + j, 0);
            vector rnd = vector cellnoise(cell);
            point c = cell + vector(0.25 + 0.5 * comp(rnd, 0), 0.25 + 0.5 * comp(rnd, 1), 0);
            float r = size * (0.6 + 0.4 * comp(rnd, 2));
            float x = distance(here, c) / r;
            h = max(h, r * sqrt(max(0, 1 - x * x)));
        }
    P += Km * h * normalize(N);
    N = calculatenormal(P);
}
