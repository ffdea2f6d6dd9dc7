#pragma once
// glint's optional modules: shared objects loaded with dlopen only when a process needs them, so
// that a process that never reads a TIFF or a .vdb never pays for loading OpenImageIO (and the
// ~260 libraries Debian's build of it pulls in) or OpenVDB. Each module exports one function,
// `glint_<name>_module`, returning a table of function pointers (the *_module.h headers); the
// table's `abi` field must equal the host's, since both are built from the same tree.
#include <string>

namespace glint {

/// The address of symbol `glint_<name>_module` in libglint_<name>.so, loaded on first use (then
/// cached). Searched in $GLINT_MODULE_PATH (colon-separated folders), the folder of the binary
/// this code is linked into, its ../lib/glint, and the build tree's folder. Throws IoError saying
/// which folders were searched and why loading failed.
void* module_entry(const std::string& name);

}  // namespace glint
