/*
 * patterns.h: the pattern helpers the corpus shaders share, in the manner of the headers every
 * public shader collection ships (noise macros, filter widths, pulses and tiles, fractal sums,
 * a cellular basis). Written for this corpus.
 *
 *   snoise(p), snoisexy(x, y), vsnoise(p)   signed noise in [-1, 1]
 *   filterwidth(x), filterwidthp(p)          how much x (or the point p) changes per sample
 *   boxstep, pulse, repeat, whichtile, odd, even, fadeout   tiling and stepping
 *   fBm, turbulence, ridgedmf               fractal sums over octaves
 *   filteredpulse                           a box-filtered pulse
 *   voronoi2d                               F1, F2 and the nearest cell's id in the plane
 */
#ifndef CORPUS_PATTERNS_H
#define CORPUS_PATTERNS_H

#ifndef MINFILTWIDTH
#define MINFILTWIDTH 1.0e-6
#endif

#define filterwidth(x) max(abs(Du(x) * du) + abs(Dv(x) * dv), MINFILTWIDTH)
#define filterwidthp(p) max(sqrt(area(p)), MINFILTWIDTH)

#define snoise(p) (2 * (float noise(p)) - 1)
#define snoisexy(x, y) (2 * (float noise(x, y)) - 1)
#define vsnoise(p) (2 * (vector noise(p)) - 1)

#define boxstep(a, b, x) clamp(((x) - (a)) / ((b) - (a)), 0, 1)
#define pulse(a, b, fuzz, x) (smoothstep((a) - (fuzz), (a), (x)) - smoothstep((b) - (fuzz), (b), (x)))
#define repeat(x, freq) (mod((x) * (freq), 1.0))
#define whichtile(x, freq) (floor((x) * (freq)))
#define odd(x) (mod((x), 2) == 1)
#define even(x) (mod((x), 2) == 0)
#define fadeout(g, g_avg, featuresize, fwidth) mix(g, g_avg, smoothstep(.2, .6, (fwidth) / (featuresize)))

/* Fractional Brownian motion: octaves of signed noise, each lacunarity times finer, gain
 * times weaker. */
float fBm(point p; uniform float octaves, lacunarity, gain)
{
    varying float sum = 0;
    varying point pp = p;
    uniform float amp = 1, i;
    for (i = 0; i < octaves; i += 1) {
        sum += amp * snoise(pp);
        amp *= gain;
        pp *= lacunarity;
    }
    return sum;
}

/* Perlin's turbulence: like fBm but of |snoise|, creased where the noise crosses zero. */
float turbulence(point p; uniform float octaves, lacunarity, gain)
{
    float sum = 0, amp = 1, i;
    point pp = p;
    for (i = 0; i < octaves; i += 1) {
        sum += amp * abs(snoise(pp));
        amp *= gain;
        pp *= lacunarity;
    }
    return sum;
}

/* Musgrave's ridged multifractal: inverted |noise| ridges, each octave weighted by the last. */
float ridgedmf(point p; uniform float octaves, lacunarity, H, offset, gain)
{
    float signal = offset - abs(snoise(p));
    signal *= signal;
    float result = signal, weight = 1, i;
    point pp = p;
    uniform float exponent = pow(lacunarity, -H);
    uniform float frequencyWeight = exponent;
    for (i = 1; i < octaves; i += 1) {
        pp *= lacunarity;
        weight = clamp(signal * gain, 0, 1);
        signal = offset - abs(snoise(pp));
        signal *= signal;
        signal *= weight;
        result += signal * frequencyWeight;
        frequencyWeight *= exponent;
    }
    return result;
}

/* The box filter of a pulse that is 1 on [edge0, edge1), over [x - dx/2, x + dx/2]. */
float filteredpulse(float edge0, edge1, x, dx)
{
    float x0 = x - dx / 2;
    float x1 = x0 + dx;
    return max(0, (min(x1, edge1) - max(x0, edge0)) / dx);
}

/* Worley's cellular basis in the plane: one feature point per integer cell, jittered by
 * cellnoise; the distances to the nearest (f1) and second nearest (f2) feature, and the nearest
 * one's cell id (a cellnoise value). */
void voronoi2d(float ss, tt, jitter; output float f1, f2, id)
{
    float cs = floor(ss), ct = floor(tt);
    float i, j;
    f1 = 4;
    f2 = 4;
    id = 0;
    for (i = -1; i <= 1; i += 1) {
        for (j = -1; j <= 1; j += 1) {
            point cell = point(cs + i + 0.5, ct + j + 0.5, 0);
            vector jit = jitter * (vector cellnoise(cs + i, ct + j) - 0.5);
            float fx = xcomp(cell) + xcomp(jit), fy = ycomp(cell) + ycomp(jit);
            float d = sqrt((ss - fx) * (ss - fx) + (tt - fy) * (tt - fy));
            if (d < f1) {
                f2 = f1;
                f1 = d;
                id = float cellnoise(cs + i, ct + j);
            } else if (d < f2) {
                f2 = d;
            }
        }
    }
}

#endif
