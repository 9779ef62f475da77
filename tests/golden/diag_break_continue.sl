// golden: compile
// break and continue need a loop, and `break N` N loops.
displacement t() {
    float i, j;
    if (u > 0) continue;
    break;
    for (i = 0; i < 2; i += 1) {
        for (j = 0; j < 2; j += 1) continue 3;
        break 2;
    }
    P += N;
}
