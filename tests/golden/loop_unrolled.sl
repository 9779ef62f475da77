// golden: compile --disasm
// A loop with a constant bound is unrolled exactly: three copies of the body, i folded in each.
displacement t() {
    float i;
    for (i = 1; i <= 3; i += 1)
        P += 0.01 * sin(u * i) * N;
}
