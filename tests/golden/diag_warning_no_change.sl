// golden: compile --disasm
// A warning only: P + 0 * k folds to P, so the programs only copy their inputs.
displacement flat(float Km = 1) {
    float k = Km * u;
    P = P + 0 * k;
}
