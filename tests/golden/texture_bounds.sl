// golden: eval --mode affine --region 0.40,0.45,0.40,0.45
// texture() over a region: the texels' range, narrowed by the lookup's Lipschitz bound about the
// region's centre (compare texture_values.sl at points).
displacement t() {
    P += texture("../../shaders/maps/tiles.exr", s, t) * normalize(N);
}
