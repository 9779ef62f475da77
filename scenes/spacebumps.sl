/*
 * spacebumps.sl (scenes/mixed.rib): a 3-D egg-crate of bumps measured in a named space, so that
 * a scene's CoordinateSystem can place the pattern independently of the surface.
 *
 *   Km          amplitude
 *   frequency   bumps per unit of the space
 *   space       the space the pattern lives in ("shader", "world", or a CoordinateSystem name)
 */
displacement spacebumps(float Km = 0.03, frequency = 4; string space = "shader")
{
    point Q = transform(space, P) * (2 * PI * frequency);
    float height = sin(xcomp(Q)) * sin(ycomp(Q)) * sin(zcomp(Q));
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
