/*
 * bricks.sl: bricks and mortar: rows offset by half a brick on alternate rows, mortar grooves
 * with bevelled edges, each brick slightly tilted by its own cellnoise. Exercises floor, mod,
 * step, smoothstep, cellnoise of two floats, and a boolean from mod.
 *
 *   Km            depth of the mortar grooves
 *   brickWidth    brick size along s (in s units)
 *   brickHeight   brick size along t
 *   mortar        mortar width (same units)
 *   bevel         width of the bevel at each brick edge
 */
displacement bricks(float Km = 0.025, brickWidth = 0.25, brickHeight = 0.08, mortar = 0.01, bevel = 0.01)
{
    float row = floor(t / brickHeight);
    float ss = s / brickWidth;
    if (mod(row, 2) >= 1)
        ss += 0.5;  // alternate rows are offset
    float column = floor(ss);
    float sb = (ss - column) * brickWidth;       // position inside the brick along s
    float tb = (t / brickHeight - row) * brickHeight;
    float w = mortar * 0.5;
    float inS = smoothstep(w, w + bevel, sb) * (1 - smoothstep(brickWidth - w - bevel, brickWidth - w, sb));
    float inT = smoothstep(w, w + bevel, tb) * (1 - smoothstep(brickHeight - w - bevel, brickHeight - w, tb));
    float tilt = (cellnoise(column, row) - 0.5) * 0.3;
    float height = inS * inT * (1 + tilt * (sb / brickWidth - 0.5)) - 1;
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
