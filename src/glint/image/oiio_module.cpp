// libglint_oiio.so: OpenImageIO's readers behind oiio_module.h.
#include "glint/image/oiio_module.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>

namespace {

void copy_error(const std::string& why, char* error, std::size_t size) {
    if (size == 0) return;
    const std::size_t n = std::min(why.size(), size - 1);
    std::memcpy(error, why.data(), n);
    error[n] = '\0';
}

void* open_image(const char* path, glint::OiioImageSpec* spec, char* error, std::size_t error_size) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::string why = OIIO::geterror();
        copy_error(why.empty() ? "cannot open it" : why, error, error_size);
        return nullptr;
    }
    const OIIO::ImageSpec& s = in->spec();
    spec->width = s.width;
    spec->height = s.height;
    spec->channels = s.nchannels;
    spec->is_float = s.format.basetype == OIIO::TypeDesc::FLOAT || s.format.basetype == OIIO::TypeDesc::HALF ||
                     s.format.basetype == OIIO::TypeDesc::DOUBLE;
    return in.release();
}

bool read_image(void* image, float* pixels, char* error, std::size_t error_size) {
    auto* in = static_cast<OIIO::ImageInput*>(image);
    if (in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, pixels)) return true;
    copy_error(in->geterror(), error, error_size);
    return false;
}

void close_image(void* image) { std::unique_ptr<OIIO::ImageInput> in(static_cast<OIIO::ImageInput*>(image)); }

const glint::OiioModule kModule{glint::kOiioModuleAbi, &open_image, &read_image, &close_image};

}  // namespace

extern "C" [[gnu::visibility("default")]] const glint::OiioModule* glint_oiio_module() { return &kModule; }
