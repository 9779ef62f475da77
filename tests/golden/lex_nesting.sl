// golden: compile --limit nesting=256
// More than 256 open parentheses at once: parsing stops (the macros expand to 272).
#define P16(x) ((((((((((((((((x))))))))))))))))
displacement t() {
    P += P16(P16(P16(P16(P16(P16(P16(P16(P16(P16(P16(P16(P16(P16(P16(P16(P16(u))))))))))))))))) * N;
}
