/*
 * dented98.sl: the "dented" displacement of the BMRT distribution (Larry Gritz, 1990s), the one
 * that 1998-era teapot scenes use, rewritten for bench/real (not shaders/dented.sl, an fBm
 * variant with parameters). Six octaves of |0.5 - noise| summed as 1/f noise in shader space;
 * the sum is cubed, so most of the surface barely moves and a few places sink deep, and the
 * point is pushed inwards (against N) by Km times that.
 *
 *   Km   depth scale of the dents (the classic teapot scene uses 2)
 */
displacement dented98(float Km = 1)
{
    float size = 1, magnitude = 0;
    float i;
    point P2 = transform("shader", P);
    for (i = 0; i < 6; i += 1) {
        magnitude += abs(.5 - noise(P2 * size)) / size;
        size *= 2;
    }
    P = P - normalize(N) * (magnitude * magnitude * magnitude) * Km;
    N = calculatenormal(P);
}
