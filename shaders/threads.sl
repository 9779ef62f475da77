/*
 * threads.sl: screw threads along t: a triangular ridge profile repeated with mod, optionally
 * rounded at the crest. Exercises mod, abs, a user function with an output parameter and
 * setzcomp-style component access.
 *
 *   Km          thread height
 *   frequency   threads per unit of t
 *   phase       shift of the threads along t
 *   crest       rounding of the crest (0: sharp)
 */
void threadProfile(float x; float crest; output float height)
{
    float tri = 1 - 2 * abs(mod(x, 1) - 0.5);  // 0 in the groove, 1 at the crest
    height = crest > 0 ? min(tri, 1 - crest) / (1 - crest) : tri;
}

displacement threads(float Km = 0.04, frequency = 10, phase = 0, crest = 0.15)
{
    float height = 0;
    threadProfile(t * frequency + phase + s * 0.5, crest, height);
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
