// golden: eval --at 0.1,0.2 --at 0.5,0.5 --at 0.9,0.75 --param Km=2
// texture(): the tiles map (shaders/maps/tiles.exr, one channel) at three points, bilinear and
// blurred, as a color (the one channel given to all three), and a missing channel's fill.
displacement t(float Km = 1) {
    string map = "../../shaders/maps/tiles.exr";
    float a = texture(map, s, t);
    float b = texture(map, s, t, "blur", 0.05, "filter", "gaussian");
    color c = texture(map, s, t);
    float d = texture(map[3], s, t, "fill", -1);
    P += Km * point(a, b + comp(c, 1), d);
}
