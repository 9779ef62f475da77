// golden: eval --mode affine --region 0.1,0.3,0.1,0.3
// Affine arithmetic keeps the correlation of u in x, y and z (compare bounds_interval.sl).
displacement t() {
    P += 0.1 * sin(u * 6) * cos(v * 6) * N - 0.5 * (u, u, u);
}
