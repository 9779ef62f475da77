// golden: compile --limit program-ops=2000000 --limit loop-iterations=100000
// 66000 values alive at once (a chain stored in an array, then read back in reverse) need more
// registers than a program can address: an error without a line.
displacement t() {
    float a[66000], i, s = 0;
    a[0] = u;
    for (i = 1; i < 66000; i += 1) a[i] = a[i - 1] * v + u;
    for (i = 65999; i >= 0; i -= 1) s = s * a[i] + a[i];
    P += s * N;
}
