// golden: compile
// Warnings only (exit 0): variables never read, also in blocks and functions. Parameters (a
// scene may set them) are not warned about.
float f(float x) {
    float y = 2;
    return x;
}
displacement t(float Km = 1) {
    float unused = 1;
    if (u > 0.5) {
        vector w = 1;
    }
    P += f(1) * N;
}
