// golden: eval --mode interval --region 0.4,0.6,0.9,1
// Issue 12: values that are infinite somewhere in the region but whose clamp is finite stay
// bounded: x divides by a range containing 0 then clamps, y is max(log(a), -6) for an a that
// reaches 0 (log is one-sided there), z is min(b, 5) for a b = exp(...) that overflows.
displacement t() {
    P = point(clamp(0.25 / (u - 0.5), -2, 2), max(log(u * (v - 0.9)), -6), min(exp(1000 * v - 200), 5));
}
