// Macros for pp_include_macros.sl, found through -I include.
#define WAVE(x, k) (0.1 / (k) * sin((x) * (k) * PI))
