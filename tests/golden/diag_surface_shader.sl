// golden: compile
// A surface shader's light loops must have a position, or a position, an axis and an angle; the
// functions affray does not give surface shaders yet are errors where they run.
surface t(float Kd = 1) {
    color C = 0;
    illuminance (P, N) {
        C += Cl;
    }
    illuminance ("key", P, N, PI / 2, 1)
        C += Cl;
    illuminance (1, N, PI / 2)
        C += Cl;
    float k = 0;
    Ci = Kd * C * lightsource("intensity", k) + environment("sky.tx", N);
}
