/*
 * paneldisp.sl: a baked displacement map per surface, as an IGES/CAD-to-RIB pipeline writes
 * it: each NuPatch gets its own instance and its own map, read over the patch's whole (s, t)
 * (the knot parameters, 0..1 on every patch of bench/real/nurbs_textured.rib). The map holds
 * heights in [0, 1] that fall to 0 at the map's border, so neighbouring patches meet without
 * cracks; bias shifts the zero level (raised and sunk detail), Km scales it in object units.
 *
 *   mapname   the patch's map (a texture made by MakeTexture in the scene)
 *   Km        height of a map value of 1, in object units
 *   bias      map value that stays on the surface
 */
displacement paneldisp(string mapname = ""; float Km = 1, bias = 0)
{
    float h = texture(mapname, s, t, "swrap", "clamp", "twrap", "clamp");
    P += Km * (h - bias) * normalize(N);
    N = calculatenormal(P);
}
