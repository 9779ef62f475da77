// tests/golden/shaders/brokensurface.sl: a surface shader that does not compile, for
// rib_surface_shader.rib (its errors are warnings there, and the surface renders as plastic).
surface brokensurface() {
    Ci = Cs * undefinedthing;
}
