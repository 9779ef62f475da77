// golden: eval --at 0.5,0.5 --param nope=1 --param Km=1,2 --param dir=1,2
// Parameter values from the command line (or a scene) are checked against the shader.
displacement t(float Km = 0.1; vector dir = (0, 0, 1)) {
    P += Km * dir;
}
