// golden: eval --at 0.25,0.5 --at 0.6,0.5
// spline with float and point knots, in several bases.
displacement t() {
    float a = spline(u, 0, 1, 4, 9, 16);
    float b = spline("linear", u, 0, 0, 1, 3, 3);
    point c = spline("bezier", v, point(0, 0, 0), point(1, 0, 0), point(1, 1, 0), point(0, 1, 1));
    P += (a, b, zcomp(c));
}
