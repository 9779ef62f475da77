// golden: compile
// Functions and globals of surface shaders: an error where the displacement shader runs them,
// a type error in any case.
color Helper(normal Nf) { return diffuse(Nf, 1) + specular(Nf, "v", 0.1); }
float Probe() { return lightsource("name", 1 + 1); }
displacement t() {
    P += diffuse(N) * N;
    P += Ci;
    Oi = 1;
    illuminance(P) { P += N; }
}
