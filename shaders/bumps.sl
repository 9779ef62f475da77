/*
 * bumps.sl: an egg-crate of bumps, the product of two sine waves across s and t.
 *
 *   Km         amplitude, in the units of the surface
 *   frequency  bumps per unit of s and of t
 */
displacement bumps(float Km = 0.04, frequency = 6)
{
    float k = 2 * PI * frequency;
    float height = Km * sin(k * s) * sin(k * t);
    P += height * normalize(N);
    N = calculatenormal(P);
}
