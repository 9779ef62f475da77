// golden: compile --disasm
// tan is one opcode (Tan), a built-in because the opcode table spells it tan(x); tan(PI / 4)
// folds to a constant by running the opcode.
displacement t() {
    P += (tan(u * 2 - 1), tan(PI / 4), 0) * N;
}
