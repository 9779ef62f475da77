// golden: eval --at 0.5,0.5 --param Km=big --param mode=1 --param nope=up
// A string value for a float parameter, a number for a string one, and an unknown name.
displacement t(float Km = 0.1; string mode = "up") {
    if (mode == "up") P += Km * N;
}
