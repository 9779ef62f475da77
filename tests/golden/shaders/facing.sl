// tests/golden/shaders/facing.sl: a surface shader for rib_surface_shader.rib: lit by its lights,
// brighter where it faces the camera.
surface facing(float Kd = 1) {
    normal Nf = faceforward(normalize(N), I);
    float facingRatio = -normalize(I) . Nf;
    Oi = Os;
    Ci = Os * Cs * (Kd * diffuse(Nf) + facingRatio * ambient());
}
