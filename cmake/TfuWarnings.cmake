# Warning and sanitizer flags for project targets only (third-party headers are SYSTEM includes).
add_library(tfu_warnings INTERFACE)
target_compile_options(tfu_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
if(TFU_WERROR)
  target_compile_options(tfu_warnings INTERFACE -Werror)
endif()
# Sanitizers (docs/fuzzing.md): every undefined-behaviour report is fatal (-fno-sanitize-recover=all),
# so that the test that triggers it fails.
#   TFU_SANITIZE (GCC or clang): ASan + UBSan. GCC's "undefined" group leaves out float-cast-overflow
#     (a NaN or huge double converted to an integer), which clang's includes; it is asked for
#     explicitly. With the sanitizers' instrumentation GCC 12's -Wmaybe-uninitialized reports false
#     positives inside libstdc++ (std::regex): off there.
#   TFU_FUZZ (clang only): the same plus libFuzzer's coverage instrumentation (fuzzer-no-link) of
#     every project target, and the libFuzzer targets (testbench/fuzz). With TFU_SANITIZE too
#     (scripts/test's sanitizer build) the tests and the fuzz targets share one compile of the
#     libraries; the tests then also carry the coverage counters, which cost them little (no
#     libFuzzer runtime is linked into them: the callbacks are the sanitizer runtime's no-ops).
if(TFU_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TFU_FUZZ needs clang: configure a build directory with CXX=clang++ (scripts/fuzz, scripts/test)")
  endif()
  target_compile_options(tfu_warnings INTERFACE -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                                                -fno-omit-frame-pointer -gline-tables-only)
  target_link_options(tfu_warnings INTERFACE -fsanitize=address,undefined)
elseif(TFU_SANITIZE)
  set(tfu_sanitizers address,undefined)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    set(tfu_sanitizers address,undefined,float-cast-overflow)
    target_compile_options(tfu_warnings INTERFACE -Wno-maybe-uninitialized)
  endif()
  target_compile_options(tfu_warnings INTERFACE -fsanitize=${tfu_sanitizers} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(tfu_warnings INTERFACE -fsanitize=${tfu_sanitizers})
endif()
