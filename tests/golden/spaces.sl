// golden: compile --disasm
// In a shader compiled alone every space is the identity: the transforms fold away, leaving
// one add per coordinate.
displacement t() {
    point q = transform("shader", P);
    vector w = vtransform("object", "world", N);
    normal n = ntransform("camera", N);
    P = transform("shader", "current", q + 0.1 * w) + 0 * n;
}
