/*
 * quilted.sl: a quilted cushion: each square puffs up between stitched seams. Constructs: sin of
 * scaled s and t, abs, pow with a fractional exponent, multiplication of two profiles.
 */
displacement quilted(float Km = 0.03, squares = 6, puff = 0.5)
{
    float a = abs(sin(PI * s * squares));
    float b = abs(sin(PI * t * squares));
    P += Km * pow(a * b, puff) * normalize(N);
    N = calculatenormal(P);
}
