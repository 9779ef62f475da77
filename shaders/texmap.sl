/*
 * texmap.sl: displacement read from a texture map, the way most production displacement is
 * painted or baked: the height is the map's value at (s, t), repeated `repeat` times across the
 * surface (the map's periodic wrap mode) and raised along the normal. Exercises texture() with a
 * string parameter as the map, blur and a filter name.
 *
 *   mapname     the map: a relative name is found beside the shader (maps/ holds the maps that
 *               tools/make_maps.sh makes)
 *   Km          height of a map value of 1
 *   repeat      copies of the map across s and t
 *   blur        blur as a fraction of the map's width
 */
displacement texmap(string mapname = "maps/tiles.exr"; float Km = 0.04, repeat = 2, blur = 0)
{
    float height = texture(mapname, s * repeat, t * repeat, "blur", blur, "filter", "box");
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
