// golden: eval --at 0.5,0.5 --at 0.25,0.25
// The shade program's N from calculatenormal, exact through dual numbers: for z = u * v the
// normal is (-v, -u, 1), unnormalised.
displacement t() {
    P += u * v * N;
    N = calculatenormal(P);
}
