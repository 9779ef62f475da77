// golden: compile
// surface(), displacement() and atmosphere() are calls in an expression (the shader keywords
// still start shader definitions): checked in a helper nobody calls, an error where the
// displacement shader runs surface() or atmosphere(); displacement() and the queries of the scene
// need a name known when the shader is compiled.
float unused() { float kd = 0; return surface("Kd", kd) + atmosphere("d", kd) + displacement("Km", kd); }
float fromSurface() { float kd = 0; surface("Kd", kd); return kd; }
displacement t(float Km = 0.1) {
    float k = 0;
    P += fromSurface() * N;
    P += atmosphere("density", k) * N;
    P += option(u > 0.5 ? "Format" : "Clipping", k) * N;
    P += displacement("Km", 1) * N;
}
