// texture/make_texture.cpp: RenderMan's MakeTexture (RI Spec 3.2 section 8.1): an image becomes a
// texture file, here the tiled, mip-mapped TIFF that OpenImageIO's maketx writes, with the wrap
// modes recorded in the file (texture() reads them as the lookups' defaults). affray's lookups
// read any image directly, so the conversion matters only to scenes whose shaders name the made
// file.
#include <OpenImageIO/imagebufalgo.h>

#include <filesystem>
#include <sstream>

#include "texture/texture.h"

namespace affray::texture {

bool MakeTexture(const std::string& picture, const std::string& output, Wrap swrap, Wrap twrap, std::string* error) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(picture, ec) || fs::is_directory(picture, ec)) {
        *error = "cannot make texture '" + output + "': image '" + picture + "' does not exist";
        return false;
    }
    OIIO::ImageSpec config;
    config.attribute("wrapmodes", std::string(WrapName(swrap)) + "," + WrapName(twrap));
    std::ostringstream messages;
    if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, picture, output, config, &messages)) {
        std::string text = messages.str();
        while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
        for (char& c : text)
            if (c == '\n') c = ' ';
        *error = "cannot make texture '" + output + "' from '" + picture + "': " + text;
        fs::remove(output, ec);  // nothing half-written left behind
        return false;
    }
    return true;
}

}  // namespace affray::texture
