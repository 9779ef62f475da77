// golden: eval --at 0.25,0.5
// What other RenderMan compilers accept: use before assignment (a warning; the value is 0),
// setycomp on a variable not yet assigned, a float promoted where a triple is expected
// (arguments, returns, ?:, comparisons, compound assignments), output parameters, shadowing,
// nested functions reading and writing their enclosing variables (with extern or without), old-style point for vector and normal, uniform and varying.
// P = (1.25, 3.5, 3), N = (0, 0, 1).
point lift(point p; float h) { return p + h; }
vector half(float x) { return x / 2; }
void bump(output point q; float by) { q += by; }
displacement t(output varying float hit = 0; uniform float k = 1) {
    float unset;
    float z = unset + 1;
    vector w;
    setycomp(w, 1);
    uniform point p = lift(0, u);
    varying point d = u > 2 ? 0 : point(1, 0, 0);
    if (p == 0.25) hit = 1;
    float k = 2;
    {
        float k = 3;
        z += k;
    }
    point v = half(2) + w;
    float depthOf() {
        extern float z;
        z += 0.0;
        return z;
    }
    float scale = 2;
    float scaled(float x) { return x * scale; }
    void grow() { scale += 1; }
    grow();
    bump(p, 1 - u);
    normal n = point(0, 0, 1);
    P = point(xcomp(p) + u, ycomp(v) + hit - 0.5 + xcomp(d) - 1 + k - 1, depthOf() - 1 + scaled(0.5) - 1.5);
    N = n;
}
