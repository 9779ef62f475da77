// golden: compile
// A space name passed to a function is checked at each call, where it is known.
float lift(string space) {
    return zcomp(vtransform(space, N));
}
displacement t() {
    P += lift("object") * N;
    P += lift("nowhere") * N;
}
