/*
 * craters.sl: a field of impact craters, one per lattice cell of (s, t) space, placed and sized by
 * cellnoise: each crater is a bowl whose floor (radius rf) rises to the rim (radius r) through
 * smoothstep(rf, r, d). The two edges both come from cellnoise and may coincide (rf == r), so
 * over a region spanning several cells the smoothstep's division is by a range containing 0:
 * its clamp to [0, 1] must keep the bound finite (issue 12). The depth is the min over the 27
 * neighbouring cells (3 x 3 x 3, the third coordinate a layer of craters).
 *
 *   Km          depth of the craters
 *   frequency   cells per unit of s and t
 */
displacement craters(float Km = 0.05, frequency = 3)
{
    point here = point(s * frequency, t * frequency, 0.5);
    point base = point(floor(xcomp(here)), floor(ycomp(here)), 0);
    float depth = 1;
    float i, j, k;
    for (i = -1; i <= 1; i += 1) {
        for (j = -1; j <= 1; j += 1) {
            for (k = -1; k <= 1; k += 1) {
                point cell = base + vector(i, j, k);
                point centre = cell + vector cellnoise(cell);
                float r = 0.2 + 0.5 * float cellnoise(cell + vector(0, 0, 17));
                float rf = r * float cellnoise(cell + vector(0, 0, 31));
                float bowl = smoothstep(rf, r, distance(here, centre));
                depth = min(depth, bowl);
            }
        }
    }
    P += Km * (depth - 1) * normalize(N);
    N = calculatenormal(P);
}
