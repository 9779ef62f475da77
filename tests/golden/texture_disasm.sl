// golden: compile --disasm
// texture(): each distinct lookup is a slot of the program (file, channel, wrap, filter, blur,
// fill), named by the Texture2 and Texture8 instructions; a color lookup of a one-channel map
// shares one slot, and a repeated lookup is computed once.
displacement t(string map = "../../shaders/maps/blobs.exr") {
    float h = texture(map, s, t, "swrap", "clamp") + texture(map, s, t, "swrap", "clamp");
    color c = texture(map, s, t, "filter", "catmull-rom");
    float q = texture(map, s, t, s + 0.01, t, s, t + 0.01, s + 0.01, t + 0.01);
    P += (h + comp(c, 0) + q) * normalize(N);
}
