/*
 * scales.sl: overlapping fish scales: rows offset by half a scale, each scale a disc rising
 * towards its lower edge. Constructs: floor, mod, a user function returning a float with early
 * return, max over the two candidate scales, clamp.
 */
float scaleHeight(float x, y)
{
    float d = sqrt(x * x + y * y);
    if (d > 1)
        return 0;
    return (1 - d) * clamp(0.5 - y, 0, 1);
}

displacement scales(float Km = 0.02, frequency = 10)
{
    float ss = s * frequency, tt = t * frequency;
    float row = floor(tt);
    float shift = mod(row, 2) * 0.5;
    float x = mod(ss + shift, 1) - 0.5;
    float y = tt - row;
    float h = max(scaleHeight(2 * x, 2 * y - 1), scaleHeight(2 * mod(ss + shift + 0.5, 1) - 1, 2 * y - 2));
    P += Km * h * normalize(N);
    N = calculatenormal(P);
}
