/*
 * fingerprint.sl: the ridges of a fingerprint: an elliptical whorl pattern (sine of a warped
 * elliptical radius, bent by the polar angle and noise). Constructs: atan, cos, sin, sqrt, noise
 * of two floats, #define'd constants.
 */
#define RIDGES 30
#define ELONG 1.6

displacement fingerprint(float Km = 0.004)
{
    float x = (s - 0.5) * ELONG, y = t - 0.45;
    float r = sqrt(x * x + y * y);
    float a = atan(y, x);
    float warp = 0.02 * cos(3 * a) + 0.03 * (float noise(s * 6, t * 6) - 0.5);
    float ridge = 0.5 + 0.5 * sin(2 * PI * RIDGES * (r + warp));
    P += Km * ridge * normalize(N);
    N = calculatenormal(P);
}
