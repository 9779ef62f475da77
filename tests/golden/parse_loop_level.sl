// golden: compile
// The N of `break N` and `continue N` is a positive integer.
displacement t() {
    float i;
    for (i = 0; i < 3; i += 1) {
        if (u > 0.5) break 0;
        if (v > 0.5) continue 1.5;
        P += N;
    }
}
