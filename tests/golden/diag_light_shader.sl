// golden: compile
// A light shader's illuminate takes a position, and optionally an axis and an angle; solar an
// axis and an angle (a solar light without one, lighting from every direction, is not supported
// yet); the functions of surface shaders are errors in it.
light t(float intensity = 1) {
    illuminate (point(0, 0, 1), vector(0, 0, 1)) {
        Cl = intensity;
    }
    solar () {
        Cl = intensity;
    }
    illuminate ("here") {
        Cl = intensity;
    }
    Cl += diffuse(N);
}
