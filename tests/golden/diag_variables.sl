// golden: compile
// Declaring, assigning and casting variables.
displacement t(string mode = "up") {
    float k = 1;
    float k = 2;
    x = 1;
    dPdu = 1;
    mode = "down";
    float f = "a";
    point q;
    P += q;
    float g = float P;
    P = point "a";
    float f2 = 1, a[2] = {1, 2}, q2;
    q2 += 1;
    f2 += P;
    P += color(1, 0, 0);
    a[0] = P;
    P += nothere * N;
    P += k * N;
    time = dtime;
}
