// golden: eval --mode interval --region 0.8,0.9,0,1
// ... and a region where some point needs more than 64 iterations is unbounded.
displacement t() {
    float n = 0;
    while (n < u * 100) n += 1;
    P += n * 0.001 * N;
}
