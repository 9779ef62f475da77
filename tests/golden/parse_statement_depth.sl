// golden: compile
// Statements nested more than 1000 deep (1001 ifs from macros) are refused once.
#define I10(s) if (u > 0) if (u > 0) if (u > 0) if (u > 0) if (u > 0) if (u > 0) if (u > 0) if (u > 0) if (u > 0) if (u > 0) s
#define I100(s) I10(I10(I10(I10(I10(I10(I10(I10(I10(I10(s))))))))))
displacement t() {
    I100(I100(I100(I100(I100(I100(I100(I100(I100(I100(if (u > 0) P += N;))))))))))
}
