// golden: eval --mode interval --region 0.1,0.3,0.1,0.3
// The same bound in interval arithmetic.
displacement t() {
    P += 0.1 * noise(P * 4) * N;
}
