/*
 * wall.sl: a wall `thickness` wide (in s) and `height` tall, standing on the patch along the line
 * s = center, with flanks that rise over `ramp` (smoothstep) so the surface stays continuous: a
 * thin feature with slopes of height / ramp (1e5 by default).
 */
displacement wall(float height = 1, thickness = 1e-4, ramp = 1e-5, center = 0.5)
{
    float half = 0.5 * thickness;
    float h = smoothstep(center - half - ramp, center - half, s) -
              smoothstep(center + half, center + half + ramp, s);
    P += height * h * normalize(N);
}
