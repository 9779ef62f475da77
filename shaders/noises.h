/*
 * noises.h: the noise helpers the shaders in this folder share (a classic RenderMan include).
 *   snoise(x)   signed noise in [-1, 1] of a float or a point
 *   snoise2(x, y)   signed noise in [-1, 1] of two floats
 *   fbm(p, octaves, lacunarity, gain)   fractional Brownian motion: octaves of signed noise,
 *               each `lacunarity` times finer and `gain` times weaker than the last
 */
#ifndef AFFRAY_NOISES_H
#define AFFRAY_NOISES_H

#define snoise(x) (2 * noise(x) - 1)
#define snoise2(x, y) (2 * noise(x, y) - 1)

float fbm(point p; float octaves, lacunarity, gain)
{
    float sum = 0, amplitude = 1, i;
    point pp = p;
    for (i = 0; i < octaves; i += 1) {
        sum += amplitude * snoise(pp);
        amplitude *= gain;
        pp *= lacunarity;
    }
    return sum;
}

#endif
