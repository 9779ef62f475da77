// golden: compile
// Function parameters have no defaults (shader parameters must have them).
float scaled(float x = 1; float s[2] = {1, 2}) {
    return x * s[0];
}
displacement t() {
    P += N;
}
