#pragma once
// The error a file or a command-line value raises when it cannot be used: one message, naming the
// file or option. (A scene's own errors, with their places, are SceneError: diagnostics.h.)
#include <stdexcept>

namespace glint {

class IoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace glint
