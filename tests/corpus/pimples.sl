/*
 * pimples.sl: sharp pimples whose height falls off as the inverse of the distance to each cell's
 * centre, capped by min. Constructs: floor, division by a distance that may reach zero, min,
 * a #define with arguments.
 */
#define CAP(x, c) min((x), (c))

displacement pimples(float Km = 0.01, frequency = 8, reach = 0.05)
{
    float ss = s * frequency, tt = t * frequency;
    float dx = ss - floor(ss) - 0.5, dy = tt - floor(tt) - 0.5;
    float d = sqrt(dx * dx + dy * dy);
    float h = CAP(reach / d, 1) - reach / 0.5;
    P += Km * max(h, 0) * normalize(N);
    N = calculatenormal(P);
}
