/*
 * droop.sl: a surface sagging under gravity along an axis: points drop along "world" -z by an
 * amount growing with the distance from a held edge, as a cloth pinned along t = 0 would.
 * Exercises a vector cast with a space, a nested function using extern, pow and vtransform.
 *
 *   amount      the drop at the far edge
 *   exponent    shape of the sag (2: parabolic)
 *   ripple      small ripple across the sag
 */
displacement droop(float amount = 0.25, exponent = 2, ripple = 0.02)
{
    float sag = 0;
    void sagAt(float x) {
        extern float sag;
        extern float exponent;
        sag = pow(clamp(x, 0, 1), exponent);
    }
    sagAt(t);
    vector down = vtransform("world", "current", vector "world" (0, 0, -1));
    P += amount * sag * down + ripple * sin(2 * PI * 3 * s) * sag * normalize(N);
    N = calculatenormal(P);
}
