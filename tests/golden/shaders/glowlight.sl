// tests/golden/shaders/glowlight.sl: a light shader for rib_surface_shader.rib: a point light of
// a category, whose colour fades with distance.
light glowlight(float intensity = 1; color lightcolor = 1; point from = point "shader" (0, 0, 0);
                string __category = "glow")
{
    illuminate (from) {
        Cl = intensity * lightcolor / (1 + length(L));
    }
}
