/*
 * bark.sl: tree bark: deep furrows along t from noise stretched lengthwise, with fine fBm between.
 * Constructs: a point with components scaled differently, 1-D noise of a float, abs, smoothstep,
 * the header's fBm.
 */
#include "patterns.h"

displacement bark(float Km = 0.05, furrows = 12, stretch = 0.15)
{
    point PP = transform("shader", P);
    point Q = point(s * furrows, t * furrows * stretch, 0);
    float wobble = 0.4 * snoise(t * 5);
    float ridge = abs(snoise(Q + vector(wobble, 0, 0)));
    float furrow = smoothstep(0.0, 0.35, ridge);
    float fine = 0.15 * fBm(PP * 20, 3, 2, 0.5);
    P += Km * (furrow + fine - 1) * normalize(N);
    N = calculatenormal(P);
}
