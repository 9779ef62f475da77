/*
 * ridge.sl: a ridge one texel wide in a 4096-texel map (ridge.exr, made by tools/make_maps.sh),
 * raised `height` along the normal. With the bilinear lookup the ridge is a tent 2/4096 wide at
 * its foot, so at the scene's resolution it is thinner than a pixel: a renderer that samples the
 * map at the pixels' rate misses it in most of them.
 */
displacement ridge(string map = "ridge.exr"; float height = 0.2)
{
    P += height * texture(map, s, t, "swrap", "clamp", "twrap", "clamp") * normalize(N);
}
