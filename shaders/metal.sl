/*
 * metal.sl: RenderMan's standard "metal" surface (RI Spec 3.2, appendix A): ambient light and a
 * highlight tinted by the surface's colour, no diffuse light.
 *
 *   Ka         ambient weight
 *   Ks         specular weight
 *   roughness  the highlight's width (its exponent is 1 / roughness)
 */
surface metal(float Ka = 1, Ks = 1, roughness = .1)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Ks * specular(Nf, V, roughness));
}
