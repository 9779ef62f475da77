// golden: compile --disasm
// User functions are inlined (no calls in the programs), an output parameter included; the
// disassembly names the lines the instructions came from.
float bump(float x, f) {
    return sin(x * f);
}
void split(float x; output float whole, fraction) {
    whole = floor(x);
    fraction = x - whole;
}
displacement t() {
    float w, f;
    split(u * 4, w, f);
    P += (bump(f, 2) + w) * 0.01 * N;
}
