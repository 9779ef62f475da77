// golden: eval --mode interval --region 0.4,0.6,0,1
// A condition undecided over the region joins both arms' values.
displacement t() {
    if (u > 0.5) P += 0.1 * N;
    else P -= 0.2 * N;
}
