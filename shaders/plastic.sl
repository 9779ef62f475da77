/*
 * plastic.sl: RenderMan's standard "plastic" surface (RI Spec 3.2, appendix A), affray's default:
 * ambient and diffuse light in the surface's colour, and a highlight in specularcolor.
 *
 *   Ka, Kd, Ks     ambient, diffuse and specular weights
 *   roughness      the highlight's width (its exponent is 1 / roughness)
 *   specularcolor  the highlight's colour
 */
surface plastic(float Ks = .5, Kd = .5, Ka = 1, roughness = .1; color specularcolor = 1)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * (Cs * (Ka * ambient() + Kd * diffuse(Nf)) + specularcolor * Ks * specular(Nf, V, roughness));
}
