/*
 * matte.sl: RenderMan's standard "matte" surface (RI Spec 3.2, appendix A): ambient and diffuse
 * light, no highlight.
 *
 *   Ka  ambient weight
 *   Kd  diffuse weight
 */
surface matte(float Ka = 1, Kd = 1)
{
    normal Nf = faceforward(normalize(N), I);
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Kd * diffuse(Nf));
}
