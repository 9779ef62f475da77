// golden: eval --at 0.25,0.5
// normalize is finite everywhere (issue 12): the zero vector normalises to itself, as in OSL (x:
// u - 0.25 is 0 here), so does a vector whose length underflows to 0 (y: before, 1e-170 times
// 1/0 was inf), and a unit vector's components are those of v/|v| clamped to [-1, 1] (z).
displacement t() {
    vector a = normalize(vector(u - 0.25, 0, 0)), b = normalize(vector(1e-170 * u, 0, 0));
    vector c = normalize(vector(v, v, v));
    P = point(xcomp(a), xcomp(b), xcomp(c));
}
