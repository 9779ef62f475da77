/*
 * tiles.sl: square ceramic tiles with rounded (cushioned) tops and grout lines; every other
 * tile in a checkerboard is raised a little. Exercises mod and floor on both axes, sqrt, max,
 * a varying if with && and ||, and a nested function definition. The tile edges are bevelled
 * (smoothstep), so the surface has no vertical walls: a wall (a jump in the displacement) is
 * geometry no bound can shrink, and grazing rays would bound every region along it.
 *
 *   Km          grout depth
 *   tiles       tiles per unit of s and t
 *   grout       grout width as a fraction of a tile
 *   cushion     how domed each tile is
 *   raise       extra height of the checkerboard's dark tiles
 *   bevel       width of the bevel from grout to tile top, as a fraction of a tile
 */
displacement tiles(float Km = 0.03, tiles = 5, grout = 0.08, cushion = 0.4, raise = 0.2, bevel = 0.05)
{
    float edgeDistance(float x) { return min(x, 1 - x); }

    float ss = s * tiles, tt = t * tiles;
    float fs = ss - floor(ss), ft = tt - floor(tt);
    float d = min(edgeDistance(fs), edgeDistance(ft));  // 0 at an edge, 0.5 at the centre
    float edge = smoothstep(grout * 0.5, grout * 0.5 + bevel, d);  // 0 in the grout, 1 on the tile
    float dome = sqrt(max(0, 1 - 4 * ((fs - 0.5) * (fs - 0.5) + (ft - 0.5) * (ft - 0.5))));
    float top = 1 + cushion * dome;
    if ((mod(floor(ss), 2) == 0 && mod(floor(tt), 2) == 0) || (mod(floor(ss), 2) == 1 && mod(floor(tt), 2) == 1))
        top += raise;
    float height = edge * top;
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
