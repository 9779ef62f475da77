/*
 * ripples.sl: concentric water ripples from a drop at (centerS, centerT), decaying outwards.
 * Constructs: a distance in (s, t), sin with a phase, exp, the divide guarded by max.
 */
displacement ripples(float Km = 0.02, frequency = 30, decay = 3, centerS = 0.5, centerT = 0.5, phase = 0)
{
    float ds = s - centerS, dt = t - centerT;
    float r = sqrt(ds * ds + dt * dt);
    float wave = sin(2 * PI * (r * frequency - phase)) * exp(-decay * r);
    wave /= max(1, 4 * r);
    P += Km * wave * normalize(N);
    N = calculatenormal(P);
}
