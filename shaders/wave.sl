/*
 * wave.sl: concentric ripples whose height decays exponentially away from a centre, the
 * displacement of Heidrich & Seidel's Figure 1 ("a wave function with exponential decay").
 *
 *   Km         amplitude, in the units of the surface
 *   frequency  ripples per unit of (s, t)
 *   decay      exponential decay rate with distance from the centre
 *   centerS/T  the centre, in (s, t)
 */
displacement wave(float Km = 0.06, frequency = 8, decay = 2.5;
                  float centerS = 0.5, centerT = 0.5;)
{
    float r = distance(point(s, t, 0), point(centerS, centerT, 0));
    float height = Km * exp(-decay * r) * cos(2 * PI * frequency * r);
    P += height * normalize(N);
    N = calculatenormal(P);
}
