/*
 * bubbles.sl: hemispherical bubbles of random radius on a grid of cells, one bubble per cell
 * where cellnoise says so. Exercises sqrt of a quantity that touches 0 at the bubble rim,
 * cellnoise with channels, the ternary on a varying condition and xcomp/ycomp. (The max
 * keeps sqrt's argument >= 0 on both arms: a bound covers both arms where the condition is
 * undecided, and sqrt of a negative range has no bound.)
 *
 *   Km          height scale
 *   frequency   cells per unit of s and t
 *   density     share of the cells that hold a bubble
 *   maxRadius   largest bubble radius, as a fraction of a cell
 */
displacement bubbles(float Km = 0.06, frequency = 6, density = 0.7, maxRadius = 0.45)
{
    point cellPoint = point(floor(s * frequency), floor(t * frequency), 0);
    point local = point(s * frequency, t * frequency, 0) - cellPoint - point(0.5, 0.5, 0);
    color random = color cellnoise(cellPoint);
    float radius = maxRadius * (0.4 + 0.6 * comp(random, 1));
    float r2 = xcomp(local) * xcomp(local) + ycomp(local) * ycomp(local);
    float inside = radius * radius - r2;
    float present = comp(random, 0) < density ? 1 : 0;
    float height = present * (inside > 0 ? sqrt(max(inside, 0)) : 0) / frequency;
    P += Km * frequency * height * normalize(N);
    N = calculatenormal(P);
}
