/*
 * needles.sl: a lattice of needle spikes h = Km * exp(-r^2 / sigma^2), r the distance in (s, t)
 * to the nearest lattice point. Unlike shaders/spikes.sl, sigma is absolute (in units of s and
 * t), so sigma = 1e-4 makes needles a thousand times thinner than a pixel of a small image:
 * a sampled renderer misses them, the guaranteed intersector may not.
 *
 *   Km          needle height
 *   sigma       needle radius, in units of s and t
 *   frequency   needles per unit of s and t (at cell centres)
 */
displacement needles(float Km = 0.3, sigma = 1e-4, frequency = 4)
{
    float cs = floor(s * frequency), ct = floor(t * frequency);
    float ds = s - (cs + 0.5) / frequency, dt = t - (ct + 0.5) / frequency;
    float height = exp(-(ds * ds + dt * dt) / (sigma * sigma));
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
