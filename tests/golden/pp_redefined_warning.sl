// golden: compile
// A warning only: the shader compiles (exit 0) with the second definition.
#define AMP 0.1
#define AMP 0.2
displacement t() {
    P += AMP * N;
}
