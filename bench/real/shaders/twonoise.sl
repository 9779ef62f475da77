/*
 * twonoise.sl: two octaves of object-space noise pressed into a surface (bench/real's
 * subdivision scene). The point is scaled by 5 in object space; a low octave a and an octave ten
 * times finer b give a depth a^2 + 0.4 b^2, always inwards along the normal.
 *
 *   Kd   depth of a value of 1
 */
displacement twonoise(float Kd = 0.1)
{
    normal Nn = normalize(N);
    point Po = transform("object", P) * 5;
    float a = noise(Po);
    float b = noise(10 * Po);
    P += Nn * Kd * (-a * a - 0.4 * b * b);
    N = calculatenormal(P);
}
