// golden: compile --limit program-ops=2000000 --limit loop-iterations=100000
// 70000 distinct constants (a loop unrolled with its counter as a factor) are more than a program
// can address: an error without a line, like the register limit (it was an abort, exit 134).
displacement t() {
    float i;
    for (i = 0; i < 70000; i += 1) P += u * i * N;
}
