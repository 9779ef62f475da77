// golden: eval --at 0.25,0.5
// RenderMan built-ins composed in the compiler: refract, fresnel (output arguments), ptlined,
// random (in [0, 1)), spline with an array of knots and the
// RiBasis name "b-spline", cellnoise and pnoise of a point and a float, mix of colors,
// comp/setcomp on colors and matrices.
displacement t() {
    vector i = normalize(vector(1, 0, -1));
    vector r = refract(i, normal(0, 0, 1), 1 / 1.5);
    float kr, kt;
    vector R, T;
    fresnel(i, normal(0, 0, 1), 1 / 1.5, kr, kt, R, T);
    float d = ptlined(point(0, 0, 0), point(1, 0, 0), point(u, v, 0)) + ptlined(0, 1, point(2, 0, 0));
    float rnd = random();
    float same = rnd >= 0 && rnd < 1 ? 1 : 0;
    float knots[5] = {0, 1, 2, 3, 4};
    float sp = spline(u, knots) + spline("b-spline", 0.5, 0, 1, 2, 3);
    float cn = cellnoise(point(u, v, 0), 0.5) - cellnoise(point(0.75, 0.75, 0), 0.5);
    float pn = pnoise(point(u, v, 0), 0.5, point(1, 1, 1), 1) - pnoise(point(u + 1, v, 0), 0.5, point(1, 1, 1), 1);
    color c = mix(color(0, 0, 0), color(1, 2, 3), 0.5);
    setcomp(c, 1, 5);
    matrix m = 1;
    setcomp(m, 3, 0, comp(c, 1));
    P = point(xcomp(r) + kr + kt + xcomp(R) - xcomp(T), d + same + cn + pn, sp + comp(c, 0) + comp(m, 3, 0));
}
