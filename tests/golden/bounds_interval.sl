// golden: eval --mode interval --region 0.1,0.3,0.1,0.3
// Interval arithmetic loses it: x - 0.5 u spans more.
displacement t() {
    P += 0.1 * sin(u * 6) * cos(v * 6) * N - 0.5 * (u, u, u);
}
