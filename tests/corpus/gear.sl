/*
 * gear.sl: a gear face: trapezoidal teeth around the rim by the polar angle, a hub boss in the
 * middle. Constructs: atan of two arguments, mod, a user function with smoothstep pulses, max,
 * degrees.
 */
float trapezoid(float x, top, slope)
{
    return smoothstep(0.5 - top / 2 - slope, 0.5 - top / 2, x) - smoothstep(0.5 + top / 2, 0.5 + top / 2 + slope, x);
}

displacement gear(float Km = 0.03, teeth = 16, rim = 0.38, hub = 0.12)
{
    float x = s - 0.5, y = t - 0.5;
    float r = sqrt(x * x + y * y);
    float a = mod(degrees(atan(y, x)) / 360 * teeth, 1);
    float tooth = trapezoid(a, 0.35, 0.1) * (1 - smoothstep(rim, rim + 0.03, r)) * smoothstep(rim - 0.08, rim - 0.05, r);
    float boss = 1 - smoothstep(hub, hub + 0.02, r);
    P += Km * max(tooth, boss) * normalize(N);
    N = calculatenormal(P);
}
