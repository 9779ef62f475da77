// golden: compile --disasm
// Algebraic identities with constants fold: x * 1, x + 0, x / 1, 1 * x, - - x; 0 * x is 0
// (x is finite wherever u is).
displacement t() {
    float x = u * 1 + 0;
    float y = 1 * (x / 1);
    float z = -(-y) + 0 * noise(P);
    P += z * N;
}
