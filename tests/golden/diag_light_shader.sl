// golden: compile
// Light, volume and imager shaders do not run yet; displacement and surface shaders do.
light t(float intensity = 1) {
    solar() {
        Cl = intensity;
    }
}
