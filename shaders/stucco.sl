/*
 * stucco.sl: plaster with raised blobs where the noise crosses a threshold, softened by
 * smoothstep. Exercises float noise of a point, smoothstep, a ternary and a varying if/else.
 *
 *   Km          height of the blobs
 *   frequency   blobs per unit of shader space
 *   threshold   noise level above which plaster rises
 *   softness    width of the rise
 */
displacement stucco(float Km = 0.03, frequency = 6, threshold = 0.55, softness = 0.08)
{
    point PP = transform("shader", P) * frequency;
    float n = float noise(PP);
    float rise = smoothstep(threshold - softness, threshold + softness, n);
    float height;
    if (n > threshold + softness)
        height = 1 + 0.3 * (n - threshold - softness);
    else
        height = rise;
    P += Km * (height > 0.001 ? height : 0) * normalize(N);
    N = calculatenormal(P);
}
