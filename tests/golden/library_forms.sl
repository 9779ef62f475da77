// golden: eval --at 0.3,0.4
// Every form of the library a displacement shader calls, in one shader: noise, pnoise and
// cellnoise of 1 to 4 dimensions with float, vector and color results; spline with a basis
// from a parameter, color and point knots, an array; filterstep's three forms; transforms by
// name and by matrix; Du, Dv, Deriv, area; faceforward, reflect, refract, rotate; comp and
// setcomp on colors and matrices; ctransform; printf; a snoise macro.
#define snoise(x) (2 * noise(x) - 1)
displacement a(float Km = 0.1; output varying float dispOut = 0; uniform string basis = "bezier";
               color tint = color "rgb" (1, 1, 1); point origin = point "shader" (0, 0, 0);)
{
    uniform float i;
    varying point PP = transform("shader", P);
    normal Nn = normalize(N);
    vector V = vector noise(PP);
    color C = color noise(PP, 0.5);
    color C2 = cellnoise(PP);
    float f1 = noise(u), f2 = noise(u, v), f3 = float noise(PP), f4 = noise(PP, 0.3);
    float p1 = pnoise(u, 4), p2 = pnoise(u, v, 4, 4), p3 = pnoise(PP, point(4, 4, 4));
    color pc = color pnoise(PP, 0.5, point 4, 2);
    float c1 = cellnoise(u), c2 = cellnoise(u, v), c3 = cellnoise(PP, 0.5);
    vector cv = vector cellnoise(u, v);
    point sp = spline(basis, u, point(0,0,0), point 1, point 2, point(3,3,3));
    color sc = spline("linear", v, color 0, color 1, color 0, color 1);
    float farr[4] = {0, 1, 0, 1};
    float sa = spline("catmull-rom", u, farr);
    float fs = filterstep(0.5, u) + filterstep(0.5, u, u + 0.1) + filterstep(0.5, u, "width", 2);
    vector t1 = ntransform("object", N) + vtransform("world", "object", V);
    point t2 = transform("shader", "current", PP) ;
    matrix m = matrix "shader" 1;
    point t3 = transform(m, P) + transform("world", m, P);
    float d = Du(u) + Dv(v) + Deriv(u * u, u) + area(P);
    vector ff = faceforward(Nn, I) + reflect(I, Nn) + refract(I, Nn, 0.9);
    point rp = rotate(P, radians(10), point 0, point(0, 0, 1));
    float a1 = atan(u) + atan(v, u) + sign(-u) + mod(u, 0.3) + abs(-v);
    color mc = mix(C, C2, 0.5);
    setcomp(mc, 0, 1);
    float mcomp = comp(mc, 1) + comp(m, 0, 0);
    color hsv = ctransform("hsv", mc);
    printf("%f %p %c\n", u, P, mc);
    float h = snoise(PP) * Km + f1 + f2 + f3 + f4 + p1 + p2 + p3 + c1 + c2 + c3 + sa + fs + d + a1 + mcomp;
    h += comp(hsv, 0) + comp(sc, 0) + xcomp(sp) + xcomp(t1) + xcomp(t2) + xcomp(t3) + xcomp(ff) + xcomp(rp) + xcomp(V) + comp(C, 0) + comp(pc, 0) + xcomp(cv);
    dispOut = h;
    P += Km * h * Nn;
    N = calculatenormal(P);
}
