// golden: compile
// A header's helpers for surface shaders (lighting, texture, illuminance, Ci and L): checked
// but never called, so the displacement shader compiles; and texture calls the default of a
// parameter rules out (in an if and in ?:).
color MaterialPlastic(normal Nf; float Ka, Kd, Ks, roughness) {
    return Ka * ambient() + Kd * diffuse(Nf) + Ks * specular(Nf, -normalize(I), roughness);
}
color GlossyLights(normal Nf; vector V; float roughness) {
    color C = 0;
    illuminance(P, Nf, PI / 2) {
        vector H = normalize(normalize(L) + V);
        C += Cl * pow(max(0, Nf . H), 1 / roughness);
    }
    return C;
}
void Shade(string map) {
    float shadowed = shadow("shad.tx", P);
    color tint = texture(map[0], s, t) * phong(N, I, 10) + trace(P, reflect(I, N));
    Ci = Cs * tint * (1 - shadowed) + environment("sky.env", vector(0, 0, 1));
    Oi = Os;
}
displacement t(string dmap = "") {
    if (dmap != "") P -= (float texture(dmap, s, t) - 0.5) * N;
    P += (dmap == "" ? 0 : float texture(dmap, s, t)) * N;
    P += 0.1 * N;
}
