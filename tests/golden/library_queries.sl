// golden: eval --at 0.25,0.5
// mix with a color t (component by component), rendererinfo, displacement() reading the
// shader's own parameter, and option/attribute/depth without a scene (eval has none: option and
// attribute answer 0, depth uses the default clipping planes 1e-10 and 1e30).
displacement q(float Km = 0.25; float freq[2] = {2, 3})
{
    color c = mix(color(0, 0, 0), color(1, 2, 4), color(0.5, 0.25, 1));
    string r;
    float version[4];
    float known = rendererinfo("renderer", r) + rendererinfo("version", version);
    float km = 0, f[2], fmt[3] = {0, 0, 0};
    known += displacement("Km", km) + displacement("freq", f) + displacement("freq", km);
    float none = option("Format", fmt) + attribute("Sides", km);
    P = point(comp(c, 0) + comp(c, 1) + comp(c, 2), known + match("affray", r), km * f[1]);
    P += vector(none, fmt[0], depth(P) * 1e29);
}
