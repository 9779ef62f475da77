// golden: eval --at 0.25,0.5
// ctransform to and from each color space, and `color "space" (...)`. P.x: the largest
// round-trip error over all spaces (0 up to rounding) of a color that varies with (u, v);
// P.y: the hue of green in hsv (1/3); P.z: the luma Y of white in YIQ (1). N: hsl's
// (2/3, 1, 1/2), pure blue, from a color cast.
float roundTrip(string space; color c) {
    color back = ctransform(space, "rgb", ctransform("rgb", space, c));
    return max(abs(comp(back - c, 0)), abs(comp(back - c, 1)), abs(comp(back - c, 2)));
}
displacement t() {
    color c = color(u, 0.5, v * 0.8);
    float err = max(roundTrip("hsv", c), roundTrip("hsl", c), roundTrip("xyz", c));
    err = max(err, roundTrip("XYZ", c), roundTrip("xyY", c));
    err = max(err, roundTrip("YIQ", c));
    color green = ctransform("hsv", color(0, 1, 0));
    color white = ctransform("rgb", "YIQ", 1);
    P = point(err, comp(green, 0), comp(white, 0));
    color blue = color "hsl" (2 / 3, 1, 0.5);
    N = normal(comp(blue, 0), comp(blue, 1), comp(blue, 2));
}
