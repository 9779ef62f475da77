// golden: eval --at 0.5,0.5 --param nope=1 --param Km=1,2 --param dir=1,2
// Parameter values from the command line are checked against the shader; a name it does not
// declare is an error here (a misspelt --param), while a scene's is ignored with a warning
// (rib_shader_parameter_undeclared.rib).
displacement t(float Km = 0.1; vector dir = (0, 0, 1)) {
    P += Km * dir;
}
