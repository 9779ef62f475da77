// golden: compile --disasm
// Dead code disappears: a value overwritten before use, and the arms that can never run with
// the noise only they read. Each program keeps the 7 instructions of its last line.
displacement t() {
    float heavy = noise(P * 10);
    float k = u * 3;
    k = v;
    if (0) P += heavy * N;
    if (1 > 2) k = heavy;
    P += k * 0.1 * N;
}
