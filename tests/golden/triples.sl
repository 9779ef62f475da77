// golden: eval --at 0.25,0.5
// Points, vectors, normals and colors: components, dot and cross, length, normalize,
// faceforward, reflect, and color arithmetic.
displacement t() {
    vector a = (u, v, 1);
    vector b = vector "world" (0, 1, 0);
    vector c = a ^ b;
    float d = a . b + length(a) + distance(P, point(0, 0, 0));
    color k = color(1, 0.5, 0.25) * 2;
    vector f = faceforward(N, vector(0, 0, 1)) + reflect(vector(1, -1, 0), vector(0, 1, 0));
    setxcomp(c, xcomp(c) + comp(k, 2));
    P = c + normalize(a) * d + f;
}
