// golden: compile
// Coordinate space names: known, not projective, strings known when compiling.
displacement t() {
    string s = "world";
    if (u > 0.5) s = "object";
    P = transform("wrold", P);
    P = transform("NDC", P);
    P = point "raster" (1, 2, 3);
    P = transform(1, P);
    P = transform(P);
    P = transform("world", color(1, 0, 0));
    P = transform(s, P);
    color c = color "hsb" (1, 0, 0);
    P += comp(c, 0) * N;
}
