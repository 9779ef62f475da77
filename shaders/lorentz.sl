/*
 * lorentz.sl: a sharp Lorentzian spike, Km / (1 + (r/width)^2), with a logarithmic skirt:
 * a division and a log whose arguments vary by orders of magnitude across the surface.
 *
 *   Km         spike height
 *   width      spike half-width, in (s, t)
 *   skirt      depth of the logarithmic skirt
 */
displacement lorentz(float Km = 0.3, width = 0.05, skirt = 0.01;
                     float centerS = 0.5, centerT = 0.5)
{
    vector d = vector(s - centerS, t - centerT, 0);
    float q = (d . d) / (width * width);
    float height = Km / (1 + q) - skirt * log(1 + q);
    P += height * normalize(N);
    N = calculatenormal(P);
}
