// golden: compile
// spline bases and knots, noise arguments, filterstep's optional parameters.
displacement t(string basis = "bezir") {
    P += spline(0.5, 1, 2, 3);
    P += spline(0.5, color(1, 1, 1), P, P, P);
    P += spline("bezir", 0.5, 1, 2, 3, 4);
    P += spline("bezier", 0.5, 1, 2, 3, 4, 5);
    P += spline(u > 0.5 ? "linear" : "bspline", 0.5, 1, 2, 3, 4);
    P += noise(color(1, 0, 0));
    P += noise(1, 2, 3);
    P += pnoise(P);
    P += filterstep(0.5, u, "blur", 1);
    P += filterstep(0.5, u, "width");
    P += filterstep(0.5, u, "width", u);
    P += filterstep(0.5);
}
