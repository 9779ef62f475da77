/*
 * record.sl: the spiral groove of a gramophone record: the polar angle and radius about the
 * centre, the groove a triangle wave of the radius advanced by the angle. Constructs: atan of two
 * arguments, sqrt, mod, abs, PI.
 */
displacement record(float Km = 0.004, grooves = 40, centerS = 0.5, centerT = 0.5)
{
    float x = s - centerS, y = t - centerT;
    float r = sqrt(x * x + y * y);
    float angle = atan(y, x) / (2 * PI);
    float g = mod(r * grooves + angle, 1);
    P -= Km * (1 - 2 * abs(g - 0.5)) * normalize(N);
    N = calculatenormal(P);
}
