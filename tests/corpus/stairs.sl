/*
 * stairs.sl: terraced rice fields: each terrace a level of its own cellnoise height, softened
 * towards the next one over a width that is random per terrace (possibly none). Constructs:
 * floor, cellnoise of a float used for both smoothstep edges, smoothstep, mix.
 */
displacement stairs(float Km = 0.05, terraces = 8, softness = 0.3)
{
    float x = t * terraces;
    float level = floor(x);
    float lo = float cellnoise(level);
    float hi = float cellnoise(level + 1);
    float edge0 = 1 - softness * float cellnoise(level + 0.5);
    float f = smoothstep(edge0, 1, x - level);
    P += Km * mix(lo, hi, f) * normalize(N);
    N = calculatenormal(P);
}
