// golden: compile
// Arguments of the built-ins lowered in compiler/lower_extras.cpp.
displacement t() {
    float kr, kt;
    fresnel(I, N, 1.5, kr, P);
    fresnel(I, N, 1.5, kr);
    P += refract(I, N) + ptlined(P, "a", P);
    P += match("(", "x") * N;
    P += match(format("%f", u), "x") * N;
    color c = ctransform("hsb", color(1, 0, 0));
    c = ctransform(concat("h", format("%d", u)), color(1, 0, 0));
    c = ctransform("hsv", P);
    printf(1);
    string s = concat("a", 1);
    P += random(1) * N;
}
