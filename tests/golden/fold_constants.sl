// golden: compile --disasm
// Constant expressions fold to one constant: arithmetic, built-ins, PI, comparisons and ?:.
// The programs keep one multiply-add per coordinate.
displacement t() {
    float k = 2 * 3 + 1;
    float s = sin(PI / 2) + sqrt(16) - abs(-1);
    float c = k > s ? 1 : 0;
    P += (k + s + c) * 0.01 * N;
}
