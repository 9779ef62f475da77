// scene/display.h: what a Display mode asks for: the channels of the image beyond RGBA. The RIB
// reader checks a mode's groups with it; the film (renderer/film.h) writes the channels it names.
#pragma once

#include <string>
#include <string_view>

namespace affray::renderer {

/// The channels a Display mode asks for beyond RGBA (which are always written).
struct DisplayChannels {
    bool z = false, n = false, p = false, st = false, cost = false, err = false;
    bool operator==(const DisplayChannels&) const = default;
};

/// Parses a Display mode: comma-separated groups, each one of "rgb", "rgba", "rgbz", "rgbaz",
/// the single letters "r" "g" "b" "a" "z", prman's "Ci" and "Oi" (colour and opacity: RGBA), or
/// the AOVs "Z" (same as "z"), "N", "P", "st",
/// "cost", "err"; spaces around a group are ignored. Returns false with *error naming the
/// offending group if a group is unknown or empty. RGBA are written whatever the mode says.
bool ParseDisplayMode(const std::string& mode, DisplayChannels* out, std::string* error);
/// Whether `group` (taken as written, spaces included) is one of the groups ParseDisplayMode
/// accepts: the RIB reader checks a Display mode with it.
bool DisplayGroupP(std::string_view group);

}  // namespace affray::renderer
