// golden: compile
// Unknown functions, a function out of its scope, and RenderMan functions not supported yet or only
// in surface shaders.
displacement t() {
    {
        float g() { return 1; }
    }
    P += g() * N;
    P += noize(P) * N;
    P += environment("sky.env", N);
    P += texture("bumps.tx") * N;
    float kd;
    P += surface("Kd", kd) * N;
}
