// golden: eval --at 0.5,0.25
// Du, Dv and Deriv (Du(x) / Du(y) + Dv(x) / Dv(y)) of f = u^2 v; area(P) is the area of the
// patch element du x dv, so area(P) / (du * dv) is |dPdu x dPdv| = 1 on the unit square.
displacement t() {
    float f = u * u * v;
    P += (Du(f), Dv(f) + Deriv(f, u + v), area(P) / (du * dv));
}
