/*
 * screwthreads.sl: a screw thread: a helix of sine ridges along t that advances with s, clipped
 * to a flat core (RenderMan Companion style). Constructs: PI, sin, max, a varying ternary.
 */
displacement screwthreads(float Km = 0.03, frequency = 12, pitch = 1, flat = 0.2)
{
    float phase = 2 * PI * (t * frequency + pitch * s);
    float ridge = 0.5 * (1 + sin(phase));
    ridge = ridge > flat ? (ridge - flat) / (1 - flat) : 0;
    P += Km * ridge * normalize(N);
    N = calculatenormal(P);
}
