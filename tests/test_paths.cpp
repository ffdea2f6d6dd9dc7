// The absolute paths of test_paths.h, from the build's compile definitions (GLINT_PATH_*).
#include "test_paths.h"

namespace glint::testing {
const char* const kSourceDir = GLINT_PATH_SOURCE_DIR;
const char* const kTestModelDir = GLINT_PATH_TEST_MODEL_DIR;
const char* const kCli = GLINT_PATH_CLI;
const char* const kMakeSky = GLINT_PATH_MAKE_SKY;
}  // namespace glint::testing
