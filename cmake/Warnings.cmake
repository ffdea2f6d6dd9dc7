# glint_warnings: an interface target carrying the project's warning flags and ISA choice.
add_library(glint_warnings INTERFACE)
target_compile_options(glint_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
  -Wcast-align -Woverloaded-virtual -Wimplicit-fallthrough)
if(GLINT_ARCH)
  target_compile_options(glint_warnings INTERFACE -march=${GLINT_ARCH})
endif()
