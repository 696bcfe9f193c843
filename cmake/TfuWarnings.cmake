# Warning and sanitizer flags for project targets only (third-party headers are SYSTEM includes).
add_library(tfu_warnings INTERFACE)
target_compile_options(tfu_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
if(TFU_WERROR)
  target_compile_options(tfu_warnings INTERFACE -Werror)
endif()
# Sanitizers (docs/fuzzing.md): every undefined-behaviour report is fatal (-fno-sanitize-recover=all),
# so that the test that triggers it fails.
# GCC's "undefined" group leaves out float-cast-overflow (a NaN or huge double converted to an
# integer), which clang's includes; it is asked for explicitly. With the sanitizers' instrumentation
# GCC 12's -Wmaybe-uninitialized reports false positives inside libstdc++ (std::regex): off here.
if(TFU_SANITIZE)
  target_compile_options(tfu_warnings INTERFACE -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer
                                                -fno-sanitize-recover=all -Wno-maybe-uninitialized)
  target_link_options(tfu_warnings INTERFACE -fsanitize=address,undefined,float-cast-overflow)
endif()
if(TFU_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TFU_FUZZ needs clang: configure a separate build directory with CXX=clang++ (scripts/fuzz)")
  endif()
  target_compile_options(tfu_warnings INTERFACE -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                                                -fno-omit-frame-pointer -gline-tables-only)
  target_link_options(tfu_warnings INTERFACE -fsanitize=address,undefined)
endif()
