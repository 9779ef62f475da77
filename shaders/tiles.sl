/*
 * tiles.sl: square ceramic tiles with rounded (cushioned) tops and grout lines; every other
 * tile in a checkerboard is raised a little. Exercises mod and floor on both axes, sqrt, max,
 * a varying if with && and ||, and a nested function definition.
 *
 *   Km          grout depth
 *   tiles       tiles per unit of s and t
 *   grout       grout width as a fraction of a tile
 *   cushion     how domed each tile is
 *   raise       extra height of the checkerboard's dark tiles
 */
displacement tiles(float Km = 0.03, tiles = 5, grout = 0.08, cushion = 0.4, raise = 0.2)
{
    float edgeDistance(float x) { return min(x, 1 - x); }

    float ss = s * tiles, tt = t * tiles;
    float fs = ss - floor(ss), ft = tt - floor(tt);
    float d = min(edgeDistance(fs), edgeDistance(ft));  // 0 at an edge, 0.5 at the centre
    float height = 0;
    if (d > grout * 0.5) {
        float dome = sqrt(max(0, 1 - 4 * ((fs - 0.5) * (fs - 0.5) + (ft - 0.5) * (ft - 0.5))));
        height = 1 + cushion * dome;
        if ((mod(floor(ss), 2) == 0 && mod(floor(tt), 2) == 0) || (mod(floor(ss), 2) == 1 && mod(floor(tt), 2) == 1))
            height += raise;
    }
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
