/*
 * defaultsurface.sl: RenderMan's "defaultsurface" (RI Spec 3.2, appendix A), a surface that needs
 * no lights: brightest where it faces the camera.
 *
 *   Ka  the light it has edge-on
 *   Kd  what facing the camera adds
 */
surface defaultsurface(float Kd = .8, Ka = .2)
{
    float facing = normalize(I) . normalize(N);
    Oi = Os;
    Ci = Os * Cs * (Ka + Kd * facing * facing);
}
