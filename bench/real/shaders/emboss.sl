/*
 * emboss.sl: a texture map raised out of the surface, after the emboss example of "Advanced
 * RenderMan" (Apodaca & Gritz, 1999, chapter 8): the map's value at (s, t), scaled and offset,
 * black outside the map, lifts the surface along N.
 *
 *   texturename          the map (heights in [0, 1]); "" displaces nothing
 *   Km                   height of a value of 1
 *   sscale, tscale       map copies per unit of s and t
 *   soffset, toffset     where the map starts in s and t
 */
displacement emboss(string texturename = ""; float Km = 0.05, sscale = 1, tscale = 1, soffset = 0, toffset = 0)
{
    if (texturename != "") {
        float ss = s * sscale - soffset;
        float tt = t * tscale - toffset;
        float amp = Km * texture(texturename, ss, tt, "swrap", "black", "twrap", "black");
        P += amp * normalize(N);
        N = calculatenormal(P);
    }
}
