/*
 * limits.sl: built-ins whose scalar result is finite although an intermediate is not, so that the
 * bound must stay finite too (issue 12): a division by a range containing 0 clamped, log near 0
 * under a max (fmax drops NaN and -inf), exp overflowing under a min, abs of an unbounded value
 * under a min, and mix, mod, floor, abs and smoothstep of bounded values.
 *
 *   Km   height of the displacement
 */
displacement limits(float Km = 0.05)
{
    float a = clamp(0.25 / (u - 0.5), -2, 2);                        // inf at u = 0.5: clamped
    float b = max(log(u * v), -6) / 6;                               // log(0) = -inf: kept >= -6
    float c = min(exp(1000 * v - 200), 5) + min(abs(log(v)), 4);     // overflow, |-inf|: min
    float d = mix(mod(7 * u, 1.5), floor(3 * v), smoothstep(0.2, 0.8, u)) + abs(sin(9 * u) - 0.5);
    P += Km * (a + b + c + d) * normalize(N);
}
