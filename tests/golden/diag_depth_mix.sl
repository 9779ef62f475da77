// golden: compile
// depth() takes one point; mix() takes a float or a triple t, and a color t mixes triples of
// x and y's own type (a point cannot be mixed into a color).
displacement t() {
    P += depth(P, 1) * N;
    P += depth("near") * N;
    color c = mix(P, P, color 1);
    P += mix(P, P, "t");
}
