// golden: compile
// A file of functions only has nothing to compile.
float twice(float x) {
    return 2 * x;
}
