// golden: compile
// Shader parameters: one of each name, with a constant default of the right type.
displacement t(float k = 1; float k = 2; string s = 1; float need; float w[2];
               float z[2] = {1, u}; float vary = u; matrix m = P) {
    P += N;
}
