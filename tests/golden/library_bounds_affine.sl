// golden: eval --mode affine --region 0.2,0.3,0.4,0.5
// Bounds of the composed built-ins over a region: ptlined (a Clamp and a length), the hue of
// ctransform("hsv") (Min, Max and a Select per sector, decided here: red is the largest), and
// fresnel's Kr (decided: no total internal reflection). Each range contains the values at
// every point of the region.
displacement t() {
    float kr, kt;
    fresnel(vector(u, 0, -1), normal(0, 0, 1), 1 / 1.5, kr, kt);
    color hsv = ctransform("hsv", color(0.9, u, v));
    P = point(ptlined(0, point(1, 0, 0), point(u, v, 0)), comp(hsv, 0), kr);
}
