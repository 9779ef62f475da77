// golden: eval --at 0.5,0.5
// texture(): a missing map with a "fill" is a warning and the fill value; a channel the map lacks
// too.
displacement t() {
    P += texture("nowhere.exr", s, t, "fill", 0.25) * normalize(N);
    P += texture("../../shaders/maps/tiles.exr"[2], s, t) * normalize(N);
}
