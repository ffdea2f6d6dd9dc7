# glint_flags: an interface target carrying the project's warnings, ISA choice and the two
# code-generation flags that let loops with sqrt and division vectorise. Neither changes a
# result (unlike -ffast-math): glint never reads errno from math functions and never enables
# floating-point traps.
add_library(glint_flags INTERFACE)
target_compile_options(glint_flags INTERFACE $<$<COMPILE_LANGUAGE:CXX>:
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
  -Wcast-align -Woverloaded-virtual -Wimplicit-fallthrough
  -fno-math-errno -fno-trapping-math>)
if(GLINT_ARCH)
  target_compile_options(glint_flags INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-march=${GLINT_ARCH}>)
endif()
