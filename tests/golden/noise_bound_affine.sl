// golden: eval --mode affine --region 0.1,0.3,0.1,0.3
// A bound on noise over a region in affine arithmetic (compare noise_bound_interval.sl).
displacement t() {
    P += 0.1 * noise(P * 4) * N;
}
