// golden: eval --mode interval --region 0.6,0.7,0,1
// A condition decided over the region runs one arm.
displacement t() {
    if (u > 0.5) P += 0.1 * N;
    else P -= 0.2 * N;
}
