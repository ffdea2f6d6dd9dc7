# GLINT_SANITIZE=address,undefined adds the sanitizers to every target (use with clang or gcc);
# C++ only: the one assembler file (the spectral table) has nothing to instrument.
if(GLINT_SANITIZE)
  add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-fsanitize=${GLINT_SANITIZE}> $<$<COMPILE_LANGUAGE:CXX>:-fno-omit-frame-pointer>)
  add_link_options(-fsanitize=${GLINT_SANITIZE})
endif()
# UndefinedBehaviorSanitizer reports abort the process (as AddressSanitizer's do), so that a
# test or a fuzzer cannot pass over them.
if(GLINT_SANITIZE MATCHES "undefined")
  add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-fno-sanitize-recover=all>)
endif()
# GLINT_FUZZ: coverage instrumentation for libFuzzer in every target (fuzz/CMakeLists.txt links
# the fuzzers' main).
if(GLINT_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "GLINT_FUZZ needs clang (CXX=clang++): libFuzzer is part of clang")
  endif()
  add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-fsanitize=fuzzer-no-link>)
endif()
