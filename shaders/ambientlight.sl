/*
 * ambientlight.sl: RenderMan's standard "ambientlight" (RI Spec 3.2, appendix A): light from no
 * direction, which ambient() sums.
 *
 *   intensity, lightcolor  its colour is their product
 */
light ambientlight(float intensity = 1; color lightcolor = 1)
{
    Cl = intensity * lightcolor;
    L = 0;
}
