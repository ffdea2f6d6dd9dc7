#pragma once
// Where the tests find the source tree, the models, the command and the sky tool: defined once, in
// test_paths.cpp, the only test file compiled with these absolute paths. Every other test file's
// compile command is then the same in any clone, so ccache serves it from a build in another
// folder (make test in a fresh clone compiles only what changed). Force-included into every test
// file (tests/CMakeLists.txt), under the names the tests have always used.
namespace glint::testing {
extern const char* const kSourceDir;
extern const char* const kTestModelDir;
extern const char* const kCli;
extern const char* const kMakeSky;
}  // namespace glint::testing

#define GLINT_SOURCE_DIR (::glint::testing::kSourceDir)
#define GLINT_TEST_MODEL_DIR (::glint::testing::kTestModelDir)
#define GLINT_CLI (::glint::testing::kCli)
#define GLINT_MAKE_SKY (::glint::testing::kMakeSky)
