# Verilator helpers for the synthesizable SystemVerilog of rtl/sv/ (TFU-D; docs/sv.md).
#
# Why not Verilator's own verilate(): it runs verilator at *configure* time, but part of our SV is
# generated at *build* time by tfu_svgen (ROM tables from the cmodel/ generators). So each model is
# verilated and compiled by a build-time custom command instead, and the Verilator runtime is
# compiled once, as the static library tfu_verilated, for all models and test executables.
#
# Provided (include this file once; rtl/sv/CMakeLists.txt does):
#
#   tfu_verilated            static library: Verilator runtime (verilated.cpp, verilated_threads.cpp)
#                            plus its include directories (SYSTEM) and VM_* definitions. Link it into
#                            every executable that uses a model (tfu_sv_model does).
#
#   tfu_sv_model(<exe>
#                PREFIX <Vname>           C++ class name of the model (header <Vname>.h)
#                TOP <module>             top module
#                SOURCES <file>...        absolute paths, packages first; generated files allowed
#                [DEPENDS <target>...]    targets that produce generated SOURCES (e.g. tfu_sv_gen)
#                [VERILATOR_ARGS <arg>...])
#       Verilates TOP at build time (verilator --cc --build, -O2) into
#       <build>/rtl/sv/obj/<Vname>/, links <Vname>__ALL.a and tfu_verilated into <exe> and adds the
#       model directory to <exe>'s include path (SYSTEM, so -Werror never sees generated code).
#       Several models (different PREFIX) go into one executable: only the small model library is
#       compiled per model, the runtime once.
#
#   tfu_sv_lint(NAME <test> TOP <module> SOURCES <file>... [DEPENDS <target>...])
#       Adds the ctest <test> (label "sv") running `verilator --lint-only -Wall` on SOURCES with top
#       TOP; any warning fails it. DEPENDS only documents the generator target: ctest runs after the
#       build, so generated files exist by then.
#
#   tfu_sv_read_manifest(<blocks.json>)
#       Reads a gate-count manifest (the format of rtl/sv/blocks.json, read by scripts/gate_count:
#       JSON array of {"block", "top", "sources": [repo-relative paths or "gen/<file>"],
#       "compare_cells"}) and sets in the caller's scope TFU_SV_BLOCKS (the block names) and, per
#       block B, TFU_SV_TOP_<B> (top module) and TFU_SV_SRC_<B> (absolute source paths; "gen/<file>"
#       becomes ${TFU_SV_GEN_DIR}/<file>). So the manifest is the one list of sources per block for
#       Verilator, lint and Yosys. Re-configures when the manifest changes.
#
#   TFU_SV_GEN_DIR           ${CMAKE_BINARY_DIR}/rtl/sv/gen: where tfu_svgen writes gen/*.sv (a
#                            generator of rtl/sv/edge/ writes its gen/ files there too, so that
#                            manifests can name them "gen/<file>")
#
# Example (a helper's rtl/sv/edge/CMakeLists.txt):
#   add_executable(tfu_sv_edge_tests test_edge_equiv.cpp)
#   target_link_libraries(tfu_sv_edge_tests PRIVATE tfu_cmodel GTest::gtest GTest::gtest_main tfu_warnings)
#   tfu_sv_model(tfu_sv_edge_tests PREFIX Vtfu_median3 TOP tfu_median3
#                SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/tfu_median3.sv)
#   tfu_sv_lint(NAME sv_lint_tfu_median3 TOP tfu_median3 SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/tfu_median3.sv)
#   tfu_gtest_suites(tfu_sv_edge_tests PREFIX "sv.edge." PROPERTIES LABELS sv TIMEOUT 300)
include_guard(GLOBAL)

find_package(verilator REQUIRED)  # Debian's verilator ships verilator-config.cmake (scripts/bootstrap)

set(TFU_SV_GEN_DIR ${CMAKE_BINARY_DIR}/rtl/sv/gen)
set(TFU_SV_OBJ_DIR ${CMAKE_BINARY_DIR}/rtl/sv/obj)

# Same definitions as Verilator's own makefiles use for a model without tracing/coverage/SystemC.
set(TFU_VERILATED_DEFS VM_COVERAGE=0 VM_SC=0 VM_TRACE=0 VM_TRACE_FST=0 VM_TRACE_VCD=0)

if(NOT TARGET tfu_verilated)
  add_library(tfu_verilated STATIC ${VERILATOR_ROOT}/include/verilated.cpp
                                   ${VERILATOR_ROOT}/include/verilated_threads.cpp)
  target_include_directories(tfu_verilated SYSTEM PUBLIC ${VERILATOR_ROOT}/include ${VERILATOR_ROOT}/include/vltstd)
  target_compile_definitions(tfu_verilated PUBLIC ${TFU_VERILATED_DEFS})
  # Third-party code: no project warnings, never -Werror.
  target_compile_options(tfu_verilated PRIVATE -w -faligned-new)
  set_target_properties(tfu_verilated PROPERTIES UNITY_BUILD OFF)  # Verilator's runtime: file by file
  target_link_libraries(tfu_verilated PUBLIC Threads::Threads)
endif()

function(tfu_sv_model exe)
  cmake_parse_arguments(M "" "PREFIX;TOP" "SOURCES;DEPENDS;VERILATOR_ARGS" ${ARGN})
  if(NOT M_PREFIX OR NOT M_TOP OR NOT M_SOURCES)
    message(FATAL_ERROR "tfu_sv_model(${exe}): PREFIX, TOP and SOURCES are required")
  endif()
  set(mdir ${TFU_SV_OBJ_DIR}/${M_PREFIX})
  file(MAKE_DIRECTORY ${mdir})
  set(lib ${mdir}/${M_PREFIX}__ALL.a)
  add_custom_command(
    OUTPUT ${lib} ${mdir}/${M_PREFIX}.h
    # MAKEFLAGS unset: verilator --build runs its own make, outside our jobserver.
    COMMAND ${CMAKE_COMMAND} -E env --unset=MAKEFLAGS --unset=MAKELEVEL
            ${VERILATOR_BIN} --cc --build -j 1 --Mdir ${mdir} --prefix ${M_PREFIX} --top-module ${M_TOP}
            -MAKEFLAGS "CXX=${CMAKE_CXX_COMPILER} OPT_FAST=-O2 OPT_SLOW=-O1 OPT_GLOBAL=-O2" ${M_VERILATOR_ARGS}
            ${M_SOURCES}
    DEPENDS ${M_SOURCES} ${M_DEPENDS}
    WORKING_DIRECTORY ${mdir}
    COMMENT "Verilating ${M_TOP} (${M_PREFIX})"
    VERBATIM)
  add_custom_target(${M_PREFIX}_model DEPENDS ${lib})
  add_dependencies(${exe} ${M_PREFIX}_model)
  target_include_directories(${exe} SYSTEM PRIVATE ${mdir})
  target_link_libraries(${exe} PRIVATE ${lib} tfu_verilated)
endfunction()

function(tfu_sv_lint)
  cmake_parse_arguments(L "" "NAME;TOP" "SOURCES;DEPENDS" ${ARGN})
  if(NOT L_NAME OR NOT L_TOP OR NOT L_SOURCES)
    message(FATAL_ERROR "tfu_sv_lint: NAME, TOP and SOURCES are required")
  endif()
  add_test(NAME ${L_NAME} COMMAND ${VERILATOR_BIN} --lint-only -Wall --top-module ${L_TOP} ${L_SOURCES})
  set_tests_properties(${L_NAME} PROPERTIES LABELS sv TIMEOUT 120)
endfunction()

function(tfu_sv_read_manifest manifest)
  file(READ ${manifest} json)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${manifest})
  string(JSON n ERROR_VARIABLE err LENGTH "${json}")
  if(err)
    message(FATAL_ERROR "${manifest}: ${err}")
  endif()
  set(blocks)
  math(EXPR last "${n} - 1")
  foreach(i RANGE ${last})
    string(JSON block GET "${json}" ${i} block)
    string(JSON top GET "${json}" ${i} top)
    string(JSON ns LENGTH "${json}" ${i} sources)
    set(srcs)
    math(EXPR slast "${ns} - 1")
    foreach(k RANGE ${slast})
      string(JSON src GET "${json}" ${i} sources ${k})
      if(src MATCHES "^gen/(.*)$")
        list(APPEND srcs ${TFU_SV_GEN_DIR}/${CMAKE_MATCH_1})
      else()
        list(APPEND srcs ${PROJECT_SOURCE_DIR}/${src})
      endif()
    endforeach()
    list(APPEND blocks ${block})
    set(TFU_SV_TOP_${block} ${top} PARENT_SCOPE)
    set(TFU_SV_SRC_${block} ${srcs} PARENT_SCOPE)
  endforeach()
  set(TFU_SV_BLOCKS ${blocks} PARENT_SCOPE)
endfunction()
