# Warnings, IEEE floating point and sanitizers for every target of the project.
#
# The oracle's numbers depend on IEEE arithmetic in the order the source states it, so no
# -ffast-math and no contraction of a*b+c into fma behind the source's back: where a fused
# multiply-add is meant, the code calls std::fma.
add_library(vt_compile_options INTERFACE)
target_compile_options(vt_compile_options INTERFACE -Wall -Wextra -Wpedantic -ffp-contract=off)
if(VT_WARNINGS_AS_ERRORS)
  target_compile_options(vt_compile_options INTERFACE -Werror)
endif()
if(VT_SANITIZE)
  target_compile_options(vt_compile_options INTERFACE -fsanitize=address,undefined
                                                      -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(vt_compile_options INTERFACE -fsanitize=address,undefined)
endif()
