/*
 * texnoise.sl: a map and a procedure together. A soft map of rolling blobs both lifts the
 * surface and sets where fine noise roughens it (a mask), and where the noise is high a second
 * map, the raised tiles, takes over (a choice between two maps by a procedural test, blended over
 * a band of the noise so that the surface has no cliff where the choice changes). Exercises
 * texture() on two maps, the Catmull-Rom filter (negative lobes: its bound widens by 9/32 of the
 * texels' range), noise, and a varying choice between lookups.
 *
 *   Km          overall height
 *   frequency   noise features per unit of s and t
 *   roughness   amplitude of the noise where the mask is 1
 */
displacement texnoise(float Km = 0.05, frequency = 12, roughness = 0.5)
{
    float mask = texture("maps/blobs.exr", s, t, "filter", "catmull-rom");
    float n = noise(s * frequency, t * frequency);
    float height = mask + roughness * mask * (n - 0.5);
    float pick = smoothstep(0.6, 0.8, n);
    if (pick > 0)
        height = mix(height, max(height, texture("maps/tiles.exr", 2 * s, 2 * t)), pick);
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
