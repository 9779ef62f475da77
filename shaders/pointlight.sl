/*
 * pointlight.sl: RenderMan's standard "pointlight" (RI Spec 3.2, appendix A): light from a point
 * in every direction, falling off with the squared distance.
 *
 *   intensity, lightcolor  its colour at distance 1 is their product
 *   from                   where it is (a point in the light's shader space)
 */
light pointlight(float intensity = 1; color lightcolor = 1; point from = point "shader" (0, 0, 0))
{
    illuminate (from) {
        Cl = intensity * lightcolor / (L . L);
    }
}
