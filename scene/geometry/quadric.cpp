// scene/geometry/quadric.cpp: names and argument checks of the quadrics (scene/geometry/quadric.h).
#include "scene/geometry/quadric.h"

#include <cmath>
#include <sstream>

namespace affray::renderer {

std::string ToString(const Quadric& q) {
    std::ostringstream out;
    out << Quadric::Name(q.kind);
    switch (q.kind) {
        case Quadric::Kind::Sphere:
        case Quadric::Kind::Cylinder:
        case Quadric::Kind::Paraboloid: out << ' ' << q.radius << ' ' << q.zmin << ' ' << q.zmax; break;
        case Quadric::Kind::Cone:
        case Quadric::Kind::Disk: out << ' ' << q.height << ' ' << q.radius; break;
        case Quadric::Kind::Torus:
            out << ' ' << q.majorRadius << ' ' << q.minorRadius << ' ' << q.phimin << ' ' << q.phimax;
            break;
        case Quadric::Kind::Hyperboloid:
            for (double x : q.point1) out << ' ' << x;
            for (double x : q.point2) out << ' ' << x;
            break;
    }
    out << ' ' << q.thetamax;
    return out.str();
}

const char* Quadric::Name(Kind kind) {
    switch (kind) {
        case Kind::Sphere: return "Sphere";
        case Kind::Cylinder: return "Cylinder";
        case Kind::Cone: return "Cone";
        case Kind::Disk: return "Disk";
        case Kind::Torus: return "Torus";
        case Kind::Hyperboloid: return "Hyperboloid";
        case Kind::Paraboloid: return "Paraboloid";
    }
    return "?";
}

std::string Quadric::Problem() const {
    const double all[] = {radius,   zmin,      zmax,      height,    majorRadius, minorRadius, phimin,   phimax,
                          thetamax, point1[0], point1[1], point1[2], point2[0],   point2[1],   point2[2]};
    for (double x : all)
        if (!std::isfinite(x)) return "its arguments must be finite";
    if (thetamax == 0) return "thetamax is 0: the surface is empty";
    switch (kind) {
        case Kind::Sphere:
            if (!(radius > 0)) return "the radius must be positive";
            if (!(std::fmin(zmax, radius) > std::fmax(zmin, -radius))) return "zmin..zmax does not cut the sphere";
            break;
        case Kind::Cylinder:
            if (!(radius > 0)) return "the radius must be positive";
            if (zmin == zmax) return "zmin equals zmax: the surface is empty";
            break;
        case Kind::Cone:
        case Kind::Disk:
            if (!(radius > 0)) return "the radius must be positive";
            break;
        case Kind::Torus:
            if (!(minorRadius > 0)) return "the minor radius must be positive";
            if (phimin == phimax) return "phimin equals phimax: the surface is empty";
            break;
        case Kind::Hyperboloid:
            if (point1[0] == point2[0] && point1[1] == point2[1] && point1[2] == point2[2])
                return "point1 equals point2: the surface is empty";
            break;
        case Kind::Paraboloid:
            if (!(radius > 0)) return "rmax must be positive";
            if (!(zmax > 0) || zmin < 0 || !(zmin < zmax)) return "it needs 0 <= zmin < zmax";
            break;
    }
    return "";
}

}  // namespace affray::renderer
