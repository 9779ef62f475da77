// golden: eval --at 0.2,0.5 --at 0.5,0.5 --at 0.8,0.5
// step, smoothstep, filterstep (with a width) and mix.
displacement t() {
    float a = step(0.5, u) + smoothstep(0.25, 0.75, u);
    float b = filterstep(0.5, u) + filterstep(0.5, u, "width", 2);
    P += (a, b, mix(-1, 1, smoothstep(0, 1, u)));
}
