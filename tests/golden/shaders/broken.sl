// A shader with an error, for rib_shader_compile_error.rib.
displacement broken(float Km = 0.1) {
    P += Km * nosuchfunction(P) * N;
}
