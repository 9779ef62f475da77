// A helper with a type error, for pp_include_error.sl.
float ripple(float x) {
    return sin(x * P);
}
