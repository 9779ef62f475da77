// golden: eval --at 0.25,0.5
// Scalar built-ins at one point.
displacement t() {
    float a = abs(-u) + sign(-v) + floor(2.5) + ceil(2.5) + round(2.5) + mod(-1, 3);
    float b = min(u, v) + max(u, v, 0.3) + clamp(2, 0, 1) + step(0.5, u) + smoothstep(0, 1, u);
    float c = mix(1, 3, u) + pow(2, 3) + sqrt(u) + inversesqrt(4) + exp(0) + log(u) + log(8, 2);
    float d = tan(u) + asin(u) + acos(u) + atan(u) + atan(v, u) + radians(180) + degrees(PI);
    P += (a, b, c + d);
}
