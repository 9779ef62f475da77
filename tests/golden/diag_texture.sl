// golden: compile
// texture(): the located errors of malformed calls and the warnings of ignored parameters.
displacement t(float b = 0.1) {
    string map = "../../shaders/maps/tiles.exr";
    P += texture(map, s) * N;
    P += texture(map, s, t, "blur", s) * N;
    P += texture(map, s, t, "filter", "sinc") * N;
    P += texture(map, s, t, "wrap", "mirror") * N;
    P += texture(map, s, t, "blur") * N;
    P += texture(map[s], s, t) * N;
    P += texture(map, P, t) * N;
    P += texture(map, s, t, "lerp", 1, "blur", b) * N;
    P += texture("nowhere.exr", s, t) * N;
    P += texture(format("%f", s), s, t) * N;
    P += texture(map, s, t, "width", "wide") * N;
}
