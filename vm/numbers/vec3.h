// vm/numbers/vec3.h: a three-component vector over any Number, for code that must run on every number
// type (base surfaces, the intersector's plane distances). GLM's vectors assume IEEE floats in
// several functions, so templated geometry uses this instead; plain double geometry uses GLM.
#pragma once

#include <type_traits>

namespace affray::vm {

template <class T>
struct Vec3 {
    T x, y, z;

    Vec3() : x(0.0), y(0.0), z(0.0) {}
    Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    template <class U>
    explicit Vec3(const Vec3<U>& o) : x(o.x), y(o.y), z(o.z) {}

    T& operator[](int i) { return i == 0 ? x : i == 1 ? y : z; }
    const T& operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }

    Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    Vec3 operator-() const { return {-x, -y, -z}; }
    Vec3 operator*(const T& s) const { return {x * s, y * s, z * s}; }
    Vec3 operator*(double s) const requires(!std::is_same_v<T, double>) { return {x * s, y * s, z * s}; }
};

template <class T>
T Dot(const Vec3<T>& a, const Vec3<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <class T>
Vec3<T> Cross(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <class T>
T Length(const Vec3<T>& a) {
    return sqrt(sqr(a.x) + sqr(a.y) + sqr(a.z));
}

template <class T>
Vec3<T> Normalize(const Vec3<T>& a) {
    T inv = T(1.0) / Length(a);
    return {a.x * inv, a.y * inv, a.z * inv};
}

}  // namespace affray::vm
