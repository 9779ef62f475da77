// golden: eval --at 0.3,0.4
// Promotions and mixing other compilers accept: float to color and point in returns,
// arguments, comparisons and ?:, a normal returned as a point, output parameters of two types,
// extern of a parameter and of globals, uniform and varying parameters, a loop summing into a
// variable never assigned (a warning). P.z = 0.1 * 13.5.
color tintOf(float x) { return x; }
point toPoint(normal n) { return n; }
float sumOf(uniform float a; varying float b) { return a + b; }
void setUp(output vector v; output color c) { v = 1; c = 0.5; }
float usesGlobals() { extern point P; extern normal N; return xcomp(P) + zcomp(N); }
displacement e(float Km = 0.1; float freq = 4)
{
    extern float Km;
    point Nf = normalize(N);
    vector vv = Nf;
    normal nn = P - point(0, 0, 0);
    color c; c = 0.5;
    vector tiny = .1;
    point p = 1;
    float hits = 0;
    if (p == 1) hits += 1;
    if (c != 0) hits += 1;
    if (N == normal(0, 0, 1)) hits += 1;
    color k = u > 0.5 ? color 1 : 0;
    vector v2; color c2;
    setUp(v2, c2);
    float sum;
    float i; for (i = 0; i < 3; i += 1) sum += i;
    float w = sumOf(1, u) + usesGlobals() + comp(tintOf(2), 1) + xcomp(toPoint(N));
    point arr[2] = {P, point(1, 2, 3)};
    P += Km * (w + sum + hits + (u > 0.5) + xcomp(vv) + xcomp(nn) + xcomp(tiny) + comp(k, 0) + xcomp(v2) + comp(c2, 0) + xcomp(arr[1])) * N;
}
