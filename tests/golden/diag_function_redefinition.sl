// golden: compile
// A function name is defined once per scope (with a note at the first definition).
float f() { return 1; }
float f() { return 2; }
displacement t() {
    float g() { return 1; }
    float g() { return 2; }
    P += (f() + g()) * N;
}
