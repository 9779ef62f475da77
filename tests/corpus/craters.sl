/*
 * craters.sl: a field of jittered craters with raised rims (aqsis's asteroid style): each cell of
 * a 3-D lattice holds a crater of random size, min over the 27 neighbours keeps the deepest.
 * Constructs: triple nested for, vector and float cellnoise of a point, length, smoothstep, min,
 * a point built from a triple, transform to "object".
 */
float crater(point p; float jitter, overlap, sharpness)
{
    point centre = (floor(xcomp(p) + 0.5), floor(ycomp(p) + 0.5), floor(zcomp(p) + 0.5));
    float amp = 0, i, j, k;
    for (i = -1; i <= 1; i += 1)
        for (j = -1; j <= 1; j += 1)
            for (k = -1; k <= 1; k += 1) {
                point c = centre + vector(i, j, k);
                c += jitter * (vector cellnoise(c) - 0.5);
                float rad = 0.5 * overlap * float cellnoise(c + vector(7, 3, 1));
                float d = length(p - c);
                amp = min(amp, smoothstep(sharpness * rad, rad, d) - 1);
            }
    return amp;
}

displacement craters(float Km = 0.06, frequency = 3, jitter = 0.6, overlap = 1, sharpness = 0.6)
{
    point Pobj = transform("object", P) * frequency;
    float h = crater(Pobj, jitter, overlap, sharpness);
    P += Km * h * normalize(N);
    N = calculatenormal(P);
}
