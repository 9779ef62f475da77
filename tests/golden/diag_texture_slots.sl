// golden: compile
// texture(): a program holds at most 256 distinct lookups (the slot is an instruction's flags byte).
displacement t() {
    float h = 0, i;
    for (i = 0; i < 257; i += 1)
        h += texture("../../shaders/maps/tiles.exr", s, t, "blur", i / 1000);
    P += h * normalize(N);
}
