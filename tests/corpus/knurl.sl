/*
 * knurl.sl: diamond knurling on a tool handle: two families of diagonal triangle waves, the
 * surface follows the lower one. Constructs: mod, abs, min, a #define with arguments.
 */
#define TRIWAVE(x) (1 - 2 * abs(mod((x), 1) - 0.5))

displacement knurl(float Km = 0.01, frequency = 20)
{
    float a = TRIWAVE((s + t) * frequency);
    float b = TRIWAVE((s - t) * frequency);
    P += Km * min(a, b) * normalize(N);
    N = calculatenormal(P);
}
