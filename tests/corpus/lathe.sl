/*
 * lathe.sl: a turned profile (beads and coves of a table leg) along t, looked up in a spline, with
 * fine tool marks across it. Constructs: spline with float knots (catmull-rom), sin, mod.
 */
displacement lathe(float Km = 0.05, marks = 60)
{
    float profile = spline(mod(t * 2, 1), 0, 0, 0.6, 1, 0.3, 0.9, 0.2, 0.5, 0.5);
    float tool = 0.03 * sin(2 * PI * marks * t);
    P += Km * (profile + tool) * normalize(N);
    N = calculatenormal(P);
}
