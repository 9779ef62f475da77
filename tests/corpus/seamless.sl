/*
 * seamless.sl: a bump pattern that tiles seamlessly across the patch's edges: octaves of
 * periodic noise whose period is the number of features per unit, displaced along a normal taken
 * to "object" space and back. Constructs: 2-D pnoise with periods, ntransform with one and two
 * spaces, a loop with two accumulators.
 */
displacement seamless(float Km = 0.02, frequency = 4, octaves = 3)
{
    float sum = 0, amp = 1, f = frequency, i;
    for (i = 0; i < octaves; i += 1) {
        sum += amp * (2 * float pnoise(s * f, t * f, f, f) - 1);
        amp *= 0.5;
        f *= 2;
    }
    normal Nobj = ntransform("object", N);
    normal Nn = normalize(ntransform("object", "current", Nobj));
    P += Km * sum * Nn;
    N = calculatenormal(P);
}
