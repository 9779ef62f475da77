/*
 * spikes.sl: a bed of needles: in every cell a Gaussian spike exp(-r^2 / sigma^2), very thin
 * when sigma is small (the thin features tessellation misses). Exercises floor, exp of a
 * large negative argument, cellnoise to vary the heights, and a constant-folded if on a
 * parameter (jitter off removes the cellnoise).
 *
 *   Km          spike height
 *   frequency   spikes per unit of s and t
 *   sigma       spike radius, as a fraction of a cell
 *   jitter      1 to vary the spike heights by cell, 0 for equal spikes
 */
displacement spikes(float Km = 0.15, frequency = 8, sigma = 0.08, jitter = 1)
{
    float cs = floor(s * frequency), ct = floor(t * frequency);
    float ls = s * frequency - cs - 0.5, lt = t * frequency - ct - 0.5;
    float height = exp(-(ls * ls + lt * lt) / (sigma * sigma));
    if (jitter != 0)
        height *= 0.5 + 0.5 * cellnoise(cs, ct);
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
