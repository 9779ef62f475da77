/*
 * spotlight.sl: RenderMan's standard "spotlight" (RI Spec 3.2, appendix A): a point light whose
 * light leaves in a cone about the direction from `from` to `to`, with a soft edge and a cosine
 * fall-off across the beam.
 *
 *   intensity, lightcolor  its colour on the axis at distance 1 is their product
 *   from, to               where it is and where it points (points in the light's shader space)
 *   coneangle              the cone's half-angle (radians)
 *   conedeltaangle         the width of its soft edge, inside the cone (radians)
 *   beamdistribution       the exponent of the cosine fall-off across the beam
 */
light spotlight(float intensity = 1; color lightcolor = 1; point from = point "shader" (0, 0, 0);
                point to = point "shader" (0, 0, 1); float coneangle = radians(30);
                float conedeltaangle = radians(5); float beamdistribution = 2)
{
    uniform vector axis = normalize(to - from);
    uniform float cosOutside = cos(coneangle), cosInside = cos(coneangle - conedeltaangle);
    illuminate (from, axis, coneangle) {
        float cosAngle = (L . axis) / length(L);
        float falloff = smoothstep(cosOutside, cosInside, cosAngle) * pow(cosAngle, beamdistribution);
        Cl = falloff * intensity * lightcolor / (L . L);
    }
}
