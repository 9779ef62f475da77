// scene/geometry/quadric.h: RenderMan's quadrics as base surfaces over (u,v), for every number type.
// Owns the (u,v) parameterisations of RI Spec 3.2, section 5.2 (Sphere, Cylinder, Cone, Disk,
// Torus, Hyperboloid, Paraboloid, each swept by u from 0 to thetamax about the z axis): one
// template evaluates a point at doubles, bounds a region with Interval or Affine, and gives exact
// tangents with Dual<T>, so a quadric is bounded by the same machinery as a displaced patch.
// The RIB's angles are in degrees; they are converted to radians once, in double, so that every
// number type multiplies by the same constants (a bound then contains the double evaluation,
// rounding included).
#pragma once

#include <cmath>
#include <numbers>
#include <string>

#include "vm/numbers/number.h"
#include "vm/numbers/vec3.h"

namespace affray::renderer {

struct Quadric {
    enum class Kind { Sphere, Cylinder, Cone, Disk, Torus, Hyperboloid, Paraboloid };
    Kind kind = Kind::Sphere;
    // The request's arguments (only those of `kind` are used); angles in degrees.
    double radius = 1;           // Sphere, Cylinder, Cone, Disk; Paraboloid's rmax
    double zmin = -1, zmax = 1;  // Sphere, Cylinder, Paraboloid
    double height = 0;           // Cone (apex height), Disk (its z)
    double majorRadius = 1, minorRadius = 0.25, phimin = 0, phimax = 360;  // Torus
    double point1[3] = {1, 0, -1}, point2[3] = {1, 0, 1};                  // Hyperboloid
    double thetamax = 360;

    /// The RIB request's name, "Sphere" etc.
    static const char* Name(Kind kind);
    /// An empty string if the arguments describe a surface, else what is wrong with them.
    std::string Problem() const;
};

/// The request with its arguments, as RIB would write it: "Sphere 1 -1 1 360".
std::string ToString(const Quadric& q);

namespace quadric_detail {
inline double Radians(double degrees) { return degrees * (std::numbers::pi / 180.0); }
/// The latitudes a sphere's zmin and zmax cut at (clamped to the poles), in radians.
inline void SphereLatitudes(const Quadric& q, double* phiMin, double* phiMax) {
    const double r = q.radius;
    *phiMin = q.zmin > -r ? std::asin(q.zmin / r) : -std::numbers::pi / 2;
    *phiMax = q.zmax < r ? std::asin(q.zmax / r) : std::numbers::pi / 2;
}
}  // namespace quadric_detail

/// The point of `q` at (u, v) in its object space (u, v in [0, 1]).
template <class T>
vm::Vec3<T> QuadricPoint(const Quadric& q, const T& u, const T& v) {
    using quadric_detail::Radians;
    const T theta = u * Radians(q.thetamax);
    switch (q.kind) {
        case Quadric::Kind::Sphere: {
            // phi runs from the latitude of zmin to that of zmax (clamped to the poles).
            const double r = q.radius;
            double phiMin, phiMax;
            quadric_detail::SphereLatitudes(q, &phiMin, &phiMax);
            const T phi = T(phiMin) + v * (phiMax - phiMin);
            const T ring = cos(phi) * r;
            return {ring * cos(theta), ring * sin(theta), sin(phi) * r};
        }
        case Quadric::Kind::Cylinder:
            return {cos(theta) * q.radius, sin(theta) * q.radius, T(q.zmin) + v * (q.zmax - q.zmin)};
        case Quadric::Kind::Cone: {
            // From the base circle (v = 0) to the apex (v = 1).
            const T ring = (T(1.0) - v) * q.radius;
            return {ring * cos(theta), ring * sin(theta), v * q.height};
        }
        case Quadric::Kind::Disk: {
            const T ring = (T(1.0) - v) * q.radius;
            return {ring * cos(theta), ring * sin(theta), T(q.height)};
        }
        case Quadric::Kind::Torus: {
            const double phiMin = Radians(q.phimin), phiMax = Radians(q.phimax);
            const T phi = T(phiMin) + v * (phiMax - phiMin);
            const T ring = cos(phi) * q.minorRadius + q.majorRadius;
            return {ring * cos(theta), ring * sin(theta), sin(phi) * q.minorRadius};
        }
        case Quadric::Kind::Hyperboloid: {
            // The segment point1 -> point2 swept about z.
            const T x = T(q.point1[0]) + v * (q.point2[0] - q.point1[0]);
            const T y = T(q.point1[1]) + v * (q.point2[1] - q.point1[1]);
            const T z = T(q.point1[2]) + v * (q.point2[2] - q.point1[2]);
            const T c = cos(theta), s = sin(theta);
            return {x * c - y * s, x * s + y * c, z};
        }
        case Quadric::Kind::Paraboloid: {
            // z from zmin to zmax; the radius grows as sqrt(z), reaching rmax at zmax.
            const T z = T(q.zmin) + v * (q.zmax - q.zmin);
            const T ring = sqrt(z * (1.0 / q.zmax)) * q.radius;
            return {ring * cos(theta), ring * sin(theta), z};
        }
    }
    return {};
}

/// A point of a surface with its tangents ∂P/∂u and ∂P/∂v (the shader's dPdu and dPdv).
template <class T>
struct SurfaceFrame {
    vm::Vec3<T> P, dPdu, dPdv;
    /// A positive multiple of dPdu x dPdv that does not vanish where the tangents do (a sphere's
    /// poles, a cone's apex), so the unit normal stays bounded there; left zero by frames that
    /// have no such form (then the normal is dPdu x dPdv normalised).
    vm::Vec3<T> normalDirection;
    bool hasNormalDirection = false;
};

/// For the quadrics swept about z, P = (ring cos theta, ring sin theta, z(v)) and
/// dPdu x dPdv = turn * ring * (cos theta z', sin theta z', -ring'): the factor turn * ring
/// vanishes on the axis (poles, apex) but the rest does not, so its direction, times the sign
/// of turn * ring, is a normal direction defined everywhere. Each case drops further positive
/// factors (r dphi for the sphere) to keep the bound's arithmetic short.
template <class T>
void QuadricNormalDirection(const Quadric& q, const T& v, const T& c, const T& s, SurfaceFrame<T>* f) {
    using quadric_detail::Radians;
    const double turnSign = q.thetamax > 0 ? 1.0 : -1.0;
    switch (q.kind) {
        case Quadric::Kind::Sphere: {
            double phiMin, phiMax;
            quadric_detail::SphereLatitudes(q, &phiMin, &phiMax);
            const T phi = T(phiMin) + v * (phiMax - phiMin);
            const T ring = cos(phi) * turnSign;
            f->normalDirection = {ring * c, ring * s, sin(phi) * turnSign};
            break;
        }
        case Quadric::Kind::Torus: {
            // ring = R + r cos phi keeps the sign of R only if |R| > r (else it crosses the axis).
            if (!(std::fabs(q.majorRadius) > q.minorRadius)) return;
            const double phiMin = Radians(q.phimin), phiMax = Radians(q.phimax);
            const double sign = turnSign * (q.majorRadius > 0 ? 1.0 : -1.0) * (phiMax > phiMin ? 1.0 : -1.0);
            const T phi = T(phiMin) + v * (phiMax - phiMin);
            const T ring = cos(phi) * sign;
            f->normalDirection = {ring * c, ring * s, sin(phi) * sign};
            break;
        }
        case Quadric::Kind::Cylinder: {
            const double sign = turnSign * (q.zmax > q.zmin ? 1.0 : -1.0);
            f->normalDirection = {c * sign, s * sign, T(0.0)};
            break;
        }
        case Quadric::Kind::Cone:
            f->normalDirection = {c * (turnSign * q.height), s * (turnSign * q.height), T(turnSign * q.radius)};
            break;
        case Quadric::Kind::Disk: f->normalDirection = {T(0.0), T(0.0), T(turnSign)}; break;
        case Quadric::Kind::Paraboloid: {
            // z = ring^2 / k^2 with k^2 = rmax^2 / zmax: the gradient (2x/k^2, 2y/k^2, -1).
            const double dz = q.zmax - q.zmin, k2 = q.radius * q.radius / q.zmax;
            const T z = T(q.zmin) + v * dz;
            const T ring = sqrt(z * (1.0 / q.zmax)) * (q.radius * 2.0 * turnSign / k2);
            f->normalDirection = {ring * c, ring * s, T(-turnSign)};
            break;
        }
        case Quadric::Kind::Hyperboloid: return;  // its line may cross the axis anywhere
    }
    f->hasNormalDirection = true;
}

/// QuadricPoint with its tangents, written out by hand rather than through Dual<T>: a T that is
/// itself a Dual (a shade program) then gets the tangents' own derivatives for free.
template <class T>
SurfaceFrame<T> QuadricFrame(const Quadric& q, const T& u, const T& v) {
    using quadric_detail::Radians;
    const double turn = Radians(q.thetamax);  // dtheta/du
    const T theta = u * turn;
    const T c = cos(theta), s = sin(theta);
    SurfaceFrame<T> f;
    f.P = QuadricPoint(q, u, v);
    // Every quadric is swept about z, so dP/du is the turn of P's (x, y).
    f.dPdu = {-f.P.y * turn, f.P.x * turn, T(0.0)};
    switch (q.kind) {
        case Quadric::Kind::Sphere:
        case Quadric::Kind::Torus: {
            // phi = phiMin + v dphi: (ring cos, ring sin, r sin phi) with ring = R + r cos phi.
            double phiMin, phiMax, r;
            if (q.kind == Quadric::Kind::Sphere) {
                r = q.radius;
                quadric_detail::SphereLatitudes(q, &phiMin, &phiMax);
            } else {
                r = q.minorRadius;
                phiMin = Radians(q.phimin), phiMax = Radians(q.phimax);
            }
            const T phi = T(phiMin) + v * (phiMax - phiMin);
            const T ringRate = sin(phi) * (-r * (phiMax - phiMin));  // d ring / dv
            f.dPdv = {ringRate * c, ringRate * s, cos(phi) * (r * (phiMax - phiMin))};
            break;
        }
        case Quadric::Kind::Cylinder: f.dPdv = {T(0.0), T(0.0), T(q.zmax - q.zmin)}; break;
        case Quadric::Kind::Cone: f.dPdv = {c * -q.radius, s * -q.radius, T(q.height)}; break;
        case Quadric::Kind::Disk: f.dPdv = {c * -q.radius, s * -q.radius, T(0.0)}; break;
        case Quadric::Kind::Hyperboloid: {
            const double dx = q.point2[0] - q.point1[0], dy = q.point2[1] - q.point1[1];
            f.dPdv = {c * dx - s * dy, s * dx + c * dy, T(q.point2[2] - q.point1[2])};
            break;
        }
        case Quadric::Kind::Paraboloid: {
            // ring = rmax sqrt(z / zmax): d ring / dv = ring / (2 z) * dz/dv (infinite at z = 0).
            const double dz = q.zmax - q.zmin;
            const T z = T(q.zmin) + v * dz;
            const T ring = sqrt(z * (1.0 / q.zmax)) * q.radius;
            const T ringRate = ring / (z * 2.0) * dz;
            f.dPdv = {ringRate * c, ringRate * s, T(dz)};
            break;
        }
    }
    QuadricNormalDirection(q, v, c, s, &f);
    return f;
}

}  // namespace affray::renderer
