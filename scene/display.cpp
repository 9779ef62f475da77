// scene/display.cpp: Display modes (scene/display.h).
#include "scene/display.h"

namespace affray::renderer {

namespace {

std::string Trim(const std::string& s) {
    size_t begin = s.find_first_not_of(" \t"), end = s.find_last_not_of(" \t");
    return begin == std::string::npos ? std::string() : s.substr(begin, end - begin + 1);
}

/// Applies one Display mode group; false if the group is not in the grammar.
bool ApplyGroup(const std::string& group, DisplayChannels* out) {
    // "Ci" and "Oi" are the output variables prman's exporters name for colour and opacity.
    static const char* const kColorGroups[] = {"rgb", "rgba", "rgbz", "rgbaz", "r", "g", "b", "a", "z", "Ci", "Oi"};
    for (const char* name : kColorGroups)
        if (group == name) {
            if (group.back() == 'z') out->z = true;  // RGBA are always written
            return true;
        }
    if (group == "Z") return out->z = true;
    if (group == "N") return out->n = true;
    if (group == "P") return out->p = true;
    if (group == "st") return out->st = true;
    if (group == "cost") return out->cost = true;
    if (group == "err") return out->err = true;
    return false;
}

}  // namespace

bool ParseDisplayMode(const std::string& mode, DisplayChannels* out, std::string* error) {
    DisplayChannels channels;
    size_t start = 0;
    while (true) {
        size_t comma = mode.find(',', start);
        const size_t length = comma == std::string::npos ? std::string::npos : comma - start;
        const std::string group = Trim(mode.substr(start, length));
        if (!ApplyGroup(group, &channels)) {
            const std::string what =
                group.empty() ? std::string("empty channel group") : "unknown channel group '" + group + "'";
            if (error)
                *error = what + " in display mode '" + mode +
                         "' (expected comma-separated rgb, rgba, rgbz, rgbaz, r, g, b, a, z, Ci, Oi, Z, N, P, st, "
                         "cost, err)";
            return false;
        }
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    *out = channels;
    return true;
}

bool DisplayGroupP(std::string_view group) {
    DisplayChannels scratch;
    return ApplyGroup(std::string(group), &scratch);
}

}  // namespace affray::renderer
