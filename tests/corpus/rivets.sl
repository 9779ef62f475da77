/*
 * rivets.sl: rows of dome-headed rivets on a plate. Constructs: mod, a distance to the cell
 * centre, sqrt of a clamped quadratic (the dome), #define, if/else on a varying test.
 */
#define SQR(x) ((x) * (x))

displacement rivets(float Km = 0.02, spacing = 0.125, radius = 0.035)
{
    float ss = mod(s, spacing) - spacing / 2;
    float tt = mod(t, spacing) - spacing / 2;
    float r2 = SQR(ss) + SQR(tt);
    float dome;
    if (r2 < SQR(radius))
        dome = sqrt(SQR(radius) - r2) / radius;
    else
        dome = 0;
    P += Km * dome * normalize(N);
    N = calculatenormal(P);
}
