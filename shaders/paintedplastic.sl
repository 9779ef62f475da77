/*
 * paintedplastic.sl: RenderMan's standard "paintedplastic" surface (RI Spec 3.2, appendix A):
 * plastic whose colour is multiplied by a texture map's, looked up at (s, t).
 *
 *   Ka, Kd, Ks     ambient, diffuse and specular weights
 *   roughness      the highlight's width (its exponent is 1 / roughness)
 *   specularcolor  the highlight's colour
 *   texturename    the map ("": none, plain plastic)
 */
surface paintedplastic(float Ks = .5, Kd = .5, Ka = 1, roughness = .1; color specularcolor = 1;
                       string texturename = "")
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color painted = 1;
    if (texturename != "")
        painted = color texture(texturename);
    Oi = Os;
    Ci = Os * (Cs * painted * (Ka * ambient() + Kd * diffuse(Nf)) + specularcolor * Ks * specular(Nf, V, roughness));
}
