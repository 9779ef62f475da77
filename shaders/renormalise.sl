/*
 * renormalise.sl: a direction turned twenty times by a small, varying vector and renormalised
 * after each turn (a loop that wraps: v = normalize(v + w*s) again and again). Its components stay
 * in [-1, 1] whatever the turns, so the bound must stay finite after any number of steps (issue
 * 12), also where v + w*s may pass through 0 (normalize of the zero vector is the zero vector).
 *
 *   Km      height of the displacement
 *   steps   how many turns
 */
displacement renormalise(float Km = 0.03, steps = 20)
{
    vector v = vector(1, 0, 0);
    vector w = vector(t - 0.5, 0.5 - s, s * t);
    float i;
    for (i = 0; i < steps; i += 1)
        v = normalize(v + w * (2 + sin(3 * s + i)));
    P += Km * (zcomp(v) + 0.5 * xcomp(v)) * normalize(N);
}
