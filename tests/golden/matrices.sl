// golden: eval --at 0.25,0.5
// Matrices: translate, rotate and scale compose (each applies before m), transform by a
// matrix, its inverse, determinant and entries.
displacement t() {
    matrix m = 1;
    m = translate(m, vector(1, 2, 3));
    m = scale(m, vector(2, 2, 2));
    m = rotate(m, PI / 2, vector(0, 0, 1));
    point q = transform(m, P);
    point back = transform(1 / m, q);
    P = q + back * 0 + (determinant(m), comp(m, 3, 0), 0) + back;
}
