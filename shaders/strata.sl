/*
 * strata.sl: layered rock: height steps through rock layers given by a spline of hardness
 * against depth, with the layers bent by periodic noise so the pattern tiles. Exercises
 * spline (Catmull-Rom) through knots, pnoise with periods, and a string parameter
 * selecting the shaping (folded at compile time).
 *
 *   Km          height scale
 *   layers      layers per unit of t
 *   warp        how much noise bends the layers
 *   shape       "terraced" or "smooth"
 */
displacement strata(float Km = 0.05, layers = 4, warp = 0.3; string shape = "terraced")
{
    float depth = t * layers + warp * pnoise(s * 4, t * 4, 4, 4);
    float phase = depth - floor(depth);
    float hardness = spline(phase, 0, 0.1, 0.9, 1, 0.35, 0.2, 0.2);
    float height = shape == "terraced" ? floor(depth) * 0.25 + hardness : depth * 0.25;
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
