/*
 * ridged.sl: Musgrave's ridged multifractal terrain: each octave folds noise into sharp ridges
 * (1 - |snoise|, squared) and is weighted by the previous octave's signal, so ridges stay sharp
 * and valleys smooth. Exercises a while loop, clamp, the snoise macro and a 2-D noise.
 *
 *   Km          terrain height
 *   frequency   base frequency in s and t
 *   octaves     octaves summed
 *   offset      ridge offset (Musgrave's "offset", about 1)
 *   gain        weight of each octave from the previous signal
 */
#include "noises.h"

displacement ridged(float Km = 0.12, frequency = 2, octaves = 4, offset = 1, gain = 2)
{
    float x = s * frequency, y = t * frequency;
    float signal = offset - abs(snoise2(x, y));
    signal *= signal;
    float result = signal, weight = 1, amplitude = 1, octave = 1;
    while (octave < octaves) {
        x *= 2.1;
        y *= 2.1;
        amplitude *= 0.5;
        weight = clamp(signal * gain, 0, 1);
        signal = offset - abs(snoise2(x, y));
        signal *= signal * weight;
        result += signal * amplitude;
        octave += 1;
    }
    P += Km * (result - 0.5) * normalize(N);
    N = calculatenormal(P);
}
