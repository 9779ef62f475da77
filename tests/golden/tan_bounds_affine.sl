// golden: eval --mode affine --region 0.1,0.3,0.1,0.3
// Affine bounds of tan: across its zero (x), on the convex side (y), and over a region holding
// the pole pi/2 (z: unbounded).
displacement t() {
    P += (tan(u - 0.2), tan(u + v), tan(u * 10 - 0.5)) * 0.01;
}
