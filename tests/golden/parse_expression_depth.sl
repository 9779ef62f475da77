// golden: compile
// Operators nested more than 1000 deep (here 1001 minus signs from macros) are refused once;
// the parse goes on.
#define M10(x) ----------x
#define M100(x) M10(M10(M10(M10(M10(M10(M10(M10(M10(M10(x))))))))))
displacement t() {
    P += M100(M100(M100(M100(M100(M100(M100(M100(M100(M100(-u)))))))))) * N;
}
