// golden: eval --at 0.05,0 --at 0.35,0 --at 0.351,0.5 --at 1,1
// A loop whose condition varies over the surface runs per point (unrolled 64 times): n ends as
// the least n with 0.1 n >= u.
displacement t() {
    float n = 0;
    while (n * 0.1 < u) n += 1;
    P += n * 0.01 * N;
}
