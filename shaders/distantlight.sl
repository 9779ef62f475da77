/*
 * distantlight.sl: RenderMan's standard "distantlight" (RI Spec 3.2, appendix A): parallel light
 * shining from `from` towards `to`, the same everywhere.
 *
 *   intensity, lightcolor  its colour is their product
 *   from, to               its direction (points in the light's shader space)
 */
light distantlight(float intensity = 1; color lightcolor = 1; point from = point "shader" (0, 0, 0);
                   point to = point "shader" (0, 0, 1))
{
    solar (to - from, 0) {
        Cl = intensity * lightcolor;
    }
}
