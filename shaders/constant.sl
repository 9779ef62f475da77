/*
 * constant.sl: RenderMan's standard "constant" surface (RI Spec 3.2, appendix A): the surface's
 * colour, unlit.
 */
surface constant()
{
    Oi = Os;
    Ci = Os * Cs;
}
