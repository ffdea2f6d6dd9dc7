# GLINT_SANITIZE=address,undefined adds the sanitizers to every target (use with clang or gcc).
if(GLINT_SANITIZE)
  add_compile_options(-fsanitize=${GLINT_SANITIZE} -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${GLINT_SANITIZE})
endif()
