/*
 * blisters.sl: paint blisters: round bumps where a noise field rises above a threshold, their
 * height a power of the excess. Constructs: noise of a point in "shader" space, a varying if
 * with no else, pow, division by a parameter.
 */
displacement blisters(float Km = 0.03, frequency = 10, threshold = 0.6, sharpness = 0.5)
{
    point PP = transform("shader", P) * frequency;
    float n = float noise(PP);
    float h = 0;
    if (n > threshold)
        h = pow((n - threshold) / (1 - threshold), sharpness);
    P += Km * h * normalize(N);
    N = calculatenormal(P);
}
