// texture/make_texture.cpp: RenderMan's MakeTexture (RI Spec 3.2 section 8.1): an image becomes a
// texture file, here the tiled, mip-mapped TIFF that OpenImageIO's maketx writes, with the wrap
// modes recorded in the file (texture() reads them as the lookups' defaults). affray's lookups
// read any image directly, so the conversion matters only to scenes whose shaders name the made
// file.
#include <filesystem>

#include "image/image_io.h"
#include "texture/texture.h"

namespace affray::texture {

bool MakeTexture(const std::string& picture, const std::string& output, Wrap swrap, Wrap twrap, std::string* error) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(picture, ec) || fs::is_directory(picture, ec)) {
        *error = "cannot make texture '" + output + "': image '" + picture + "' does not exist";
        return false;
    }
    std::string why;
    const image::io::ImageIo* images = image::io::Get(&why);
    if (!images ||
        !images->MakeTx(picture, output, std::string(WrapName(swrap)) + "," + WrapName(twrap), std::nullopt, &why)) {
        *error = "cannot make texture '" + output + "' from '" + picture + "': " + why;
        fs::remove(output, ec);  // nothing half-written left behind
        return false;
    }
    return true;
}

}  // namespace affray::texture
