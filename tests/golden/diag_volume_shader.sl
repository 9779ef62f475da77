// golden: compile
// Volume and imager shaders do not run yet; displacement, surface and light shaders do.
volume t(float density = 1) {
    Ci = Ci * density;
}
