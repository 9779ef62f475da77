/*
 * rings.sl: ripples spreading from three drops, summed: each a decaying cosine of the distance
 * from its centre (the drops' positions and strengths are array parameters). Exercises array
 * parameters of points and floats with a varying-free loop over them, distance and exp.
 *
 *   Km          ripple height
 *   frequency   ripples per unit of (s, t)
 *   decay       decay with distance
 *   centres     the drops, in (s, t) (z ignored)
 *   strength    each drop's relative height
 */
displacement rings(float Km = 0.03, frequency = 10, decay = 3;
                   point centres[3] = {(0.3, 0.3, 0), (0.7, 0.4, 0), (0.45, 0.75, 0)};
                   float strength[3] = {1, 0.7, 0.5})
{
    point here = point(s, t, 0);
    float height = 0, i;
    for (i = 0; i < 3; i += 1) {
        float r = distance(here, centres[i]);
        height += strength[i] * exp(-decay * r) * cos(2 * PI * frequency * r);
    }
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
