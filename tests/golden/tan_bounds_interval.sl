// golden: eval --mode interval --region 0.1,0.3,0.1,0.3
// The same bounds in interval arithmetic (compare tan_bounds_affine.sl).
displacement t() {
    P += (tan(u - 0.2), tan(u + v), tan(u * 10 - 0.5)) * 0.01;
}
