// golden: compile
// Garbage between definitions is skipped token by token up to the next shader or function.
float f(float x) { return 2 * x; }
42 + ;
displacement t() {
    P += f(u) * N;
}
