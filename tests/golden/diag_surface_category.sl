// golden: compile
// The category of a light loop is a constant string: which lights it visits is decided when the
// shader is compiled for its scene.
surface t(string which = "key") {
    string named = concat(which, format("%f", u));
    illuminance (named, P) {
        Ci += Cl;
    }
}
