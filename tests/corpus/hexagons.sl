/*
 * hexagons.sl: hexagonal tiles with grooves between them: the point is mapped to the nearer of
 * two offset rectangular lattices' centres, the groove depth from the hexagon distance.
 * Constructs: floor, a user function with output parameters, max and abs, ternaries, sqrt(3).
 */
void hexCentre(float x, y; output float cx, cy)
{
    float h = sqrt(3);
    float ax = floor(x) + 0.5, ay = (floor(y / h) + 0.5) * h;
    float bx = floor(x + 0.5), by = floor(y / h + 0.5) * h;
    float da = (x - ax) * (x - ax) + (y - ay) * (y - ay);
    float db = (x - bx) * (x - bx) + (y - by) * (y - by);
    cx = da < db ? ax : bx;
    cy = da < db ? ay : by;
}

displacement hexagons(float Km = 0.02, frequency = 8, groove = 0.06)
{
    float x = s * frequency, y = t * frequency, cx, cy;
    hexCentre(x, y, cx, cy);
    float dx = abs(x - cx), dy = abs(y - cy);
    float hexd = max(dx, 0.5 * dx + 0.5 * sqrt(3) * dy);  /* 0.5 on the hexagon's edge */
    P += Km * (smoothstep(0.5, 0.5 - groove, hexd) - 1) * normalize(N);
    N = calculatenormal(P);
}
