/*
 * cellular.sl: Worley cellular texture: each integer cell holds one feature point placed by
 * cellnoise; the displacement is the distance to the nearest (F1) minus a share of the second
 * nearest (F2), giving scales or cobblestones. Exercises nested for loops, a vector cellnoise,
 * arrays and comparisons in a loop.
 *
 *   Km          height of the cells
 *   frequency   cells per unit of s and t
 *   jitter      how far feature points stray from the cell centres (0..1)
 *   f2weight    weight of F2 (0: F1 only)
 */
displacement cellular(float Km = 0.04, frequency = 5, jitter = 0.9, f2weight = 0.6)
{
    point here = point(s * frequency, t * frequency, 0);
    float cs = floor(xcomp(here)), ct = floor(ycomp(here));
    float nearest[2] = {10, 10};
    float i, j;
    for (i = -1; i <= 1; i += 1) {
        for (j = -1; j <= 1; j += 1) {
            point cell = point(cs + i, ct + j, 0);
            vector offset = vector cellnoise(cell);
            point feature = cell + point(0.5, 0.5, 0) + jitter * (offset - vector(0.5, 0.5, 0.5));
            setzcomp(feature, 0);
            float d = distance(here, feature);
            if (d < nearest[0]) {
                nearest[1] = nearest[0];
                nearest[0] = d;
            } else if (d < nearest[1]) {
                nearest[1] = d;
            }
        }
    }
    float height = nearest[0] - f2weight * nearest[1];
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
