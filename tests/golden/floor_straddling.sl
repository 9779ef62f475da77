// golden: eval --mode affine --region 0.2,0.3,0,1
// floor(u * 4) straddles 1 over the region: it runs once per side and joins the results, so
// the bound is the two steps [0, 0.1], not a ramp.
displacement t() {
    P += floor(u * 4) * 0.1 * N;
}
