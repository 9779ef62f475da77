// rib/detail.cpp: levels of detail (RI 3.2 section 4.1.7). `Detail` gives a bound in object space,
// `DetailRange` the sizes on screen at which the primitives that follow are drawn, and
// `RelativeDetail` scales every size. The size, the detail, is the raster area in pixels of the
// box around the bound's projected corners, times RelativeDetail; it is measured at the
// DetailRange request, whose primitives are then kept or dropped (rib.cpp), so a level that is not
// drawn is not kept and costs no render time.
//
// Where RenderMan dissolves one level into the next across a transition (the level's weight rises
// from 0 at minvisible to 1 at lowertransition and falls back to 0 from uppertransition to
// maxvisible), affray draws one level at every size, switching in the middle of the transition,
// where the two levels weigh one half each; at exactly the middle the finer level, whose weight
// rises, is drawn. So a level is drawn for
//     (minvisible + lowertransition) / 2 <= detail < (uppertransition + maxvisible) / 2,
// with one note per file. A bound reaching behind the eye of a perspective camera has an
// unbounded detail, as has a range without any Detail bound (warned about): the level drawn is the
// one whose maxvisible is infinite (1e30 or more, as exporters write it), the finest.
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "rib/parser.h"
#include "scene/geometry/camera.h"

namespace affray::rib {

// Detail xmin xmax ymin ymax zmin zmax: the bound of the levels that follow, in the current
// object space (an attribute); kept as its corners in camera space.
bool RibParser::DoDetail(const RibRequest& r) {
    double b[6];
    if (!Numbers(r, 6, "xmin xmax ymin ymax zmin zmax", b)) return false;
    for (int i = 0; i < 6; i += 2)
        if (!(std::isfinite(b[i]) && std::isfinite(b[i + 1]) && b[i] <= b[i + 1]))
            return Fail(r.at, "'Detail' expects a finite bound with each minimum at most its maximum, got " +
                                  FormatNumber(b[i]) + " > " + FormatNumber(b[i + 1]));
    const glm::dmat4 toCamera = ObjectToCamera();
    auto corners = std::make_shared<std::array<glm::dvec3, 8>>();
    for (int i = 0; i < 8; ++i)
        (*corners)[i] = glm::dvec3(toCamera * glm::dvec4(b[i & 1], b[2 + ((i >> 1) & 1)], b[4 + (i >> 2)], 1.0));
    m_state.detailBound = std::move(corners);
    return true;
}

// RelativeDetail scale: every detail is multiplied by it (an option). Given inside the world
// block, where options no longer apply, it is ignored with a warning, as prman does.
bool RibParser::DoRelativeDetail(const RibRequest& r) {
    double scale;
    if (!Numbers(r, 1, "relativedetail", &scale)) return false;
    if (!(scale > 0 && std::isfinite(scale)))
        return Fail(r.at, "'RelativeDetail' must be positive, got " + FormatNumber(scale));
    if (m_worldSeen && !m_worldEnded) {
        Warn(r.at, "'RelativeDetail' is an option and applies only before 'WorldBegin'; ignored");
        return true;
    }
    m_relativeDetail = scale;
    return true;
}

// DetailRange minvisible lowertransition uppertransition maxvisible: whether the primitives that
// follow are drawn (the head comment).
bool RibParser::DoDetailRange(const RibRequest& r) {
    double v[4];
    if (!Numbers(r, 4, "minvisible lowertransition uppertransition maxvisible", v)) return false;
    if (!(v[0] >= 0 && v[0] <= v[1] && v[1] <= v[2] && v[2] <= v[3]))
        return Fail(r.at,
                    "'DetailRange' expects 0 <= minvisible <= lowertransition <= uppertransition <= maxvisible, got " +
                        FormatNumber(v[0]) + " " + FormatNumber(v[1]) + " " + FormatNumber(v[2]) + " " +
                        FormatNumber(v[3]));
    if (!InsideWorld(r)) return false;
    double detail = std::numeric_limits<double>::infinity();
    if (!m_state.detailBound) {
        Warn(r.at,
             "'DetailRange' without a 'Detail' bound: its detail is taken as unbounded (the level "
             "whose maxvisible is infinite is drawn)");
    } else {
        const renderer::Camera camera(m_scene.camera);
        glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
        bool front = true;
        for (const glm::dvec3& corner : *m_state.detailBound) {
            glm::dvec2 raster;
            if (!camera.ToRaster(corner, &raster)) {
                front = false;
                break;
            }
            lo = glm::min(lo, raster);
            hi = glm::max(hi, raster);
        }
        if (front) detail = (hi.x - lo.x) * (hi.y - lo.y) * m_relativeDetail;
    }
    // A maxvisible of 1e30 or more is the exporters' infinity (1e38 is common): such a level is
    // drawn at any larger size, unbounded ones included.
    const double from = 0.5 * (v[0] + v[1]), to = 0.5 * (v[2] + v[3]);
    m_state.detailHidden = !(detail >= from && (detail < to || v[3] >= 1e30));
    if (v[0] < v[1] || v[2] < v[3])
        Note(r.at,
             "'DetailRange' transitions are not dissolved: each level is drawn up to the middle of its "
             "transitions");
    return true;
}

}  // namespace affray::rib
