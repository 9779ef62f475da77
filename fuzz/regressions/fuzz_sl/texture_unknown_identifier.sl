displacement t() { float h = texture(maq); P += h * N; }
