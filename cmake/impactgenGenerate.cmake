# impactgen_generate(): generate a C++ impact solver for your own problem at
# build time, the way flatbuffers_generate_headers() or protobuf_generate() do.
#
#   impactgen_generate(<target>
#                      PROBLEM <file.json>
#                      [NAME <function>]
#                      [NAMESPACE <namespace>]
#                      [PARAMS <symbol>...])
#
# Runs, at build time,
#
#   impactgen codegen <file.json> --output <dir>/<target>.hpp --name <function>
#                     [--namespace <namespace>] [--params a,b,c]
#
# and defines an INTERFACE library <target> whose include directory holds
# <target>.hpp, so that
#
#   target_link_libraries(app PRIVATE <target>)
#
# lets app's sources `#include "<target>.hpp"`. The header is regenerated when
# the problem file or the impactgen executable changes.
#
#   PROBLEM    the problem in the impact problem format (symbols for the values
#              that are arguments of the generated function). A relative path
#              is taken relative to CMAKE_CURRENT_SOURCE_DIR.
#   NAME       the generated function's name; default: <target> made into a C
#              identifier.
#   NAMESPACE  the C++ namespace of the generated code (may be nested, a::b);
#              default: impactgen::generated.
#   PARAMS     the symbols (or quantity names such as m1, v_x_ball) that stay
#              parameters of the generated function, in this order; every other
#              value of the problem is folded in as a constant, so every symbol
#              of the problem must be listed. Default: all the problem's
#              symbols, in the order they appear in the problem.
#
# The generated header is plain C++17 with no dependency, so <target> links to
# nothing. The executable run is the target impactgen::impactgen: the imported
# one of an installed impactgen (find_package(impactgen CONFIG)), or the one
# built in the same tree.

include_guard(GLOBAL)

function(impactgen_generate target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "PROBLEM;NAME;NAMESPACE" "PARAMS")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "impactgen_generate(${target}): unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(arg_KEYWORDS_MISSING_VALUES)
    message(FATAL_ERROR "impactgen_generate(${target}): no value given for ${arg_KEYWORDS_MISSING_VALUES}")
  endif()
  if(NOT arg_PROBLEM)
    message(FATAL_ERROR "impactgen_generate(${target}): PROBLEM <file.json> is required")
  endif()
  if(TARGET ${target})
    message(FATAL_ERROR "impactgen_generate(${target}): a target named ${target} already exists")
  endif()
  if(NOT TARGET impactgen::impactgen)
    message(FATAL_ERROR "impactgen_generate(${target}): the target impactgen::impactgen does not exist; "
                        "call find_package(impactgen CONFIG REQUIRED) first")
  endif()

  get_filename_component(problem "${arg_PROBLEM}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  get_source_file_property(problem_is_generated "${problem}" GENERATED)
  if(NOT EXISTS "${problem}" AND NOT problem_is_generated)
    message(FATAL_ERROR "impactgen_generate(${target}): problem file ${problem} does not exist")
  endif()

  if(arg_NAME)
    set(function_name "${arg_NAME}")
  else()
    string(MAKE_C_IDENTIFIER "${target}" function_name)
  endif()

  set(include_dir "${CMAKE_CURRENT_BINARY_DIR}/impactgen/${target}")
  set(header "${include_dir}/${target}.hpp")

  set(options --name "${function_name}")
  if(arg_NAMESPACE)
    list(APPEND options --namespace "${arg_NAMESPACE}")
  endif()
  if(arg_PARAMS)
    list(JOIN arg_PARAMS "," params)
    list(APPEND options --params "${params}")
  endif()

  # The stamp records that the command ran, so the rule is up to date even
  # when impactgen leaves an unchanged header untouched (users of an unchanged
  # solver then do not recompile). DEPENDS on the executable target: a target-level dependency
  # when impactgen is built in this tree, and a file-level one on the built or
  # the imported executable, so that a new impactgen regenerates the header.
  set(stamp "${CMAKE_CURRENT_BINARY_DIR}/impactgen/${target}.stamp")
  add_custom_command(
    OUTPUT "${stamp}"
    BYPRODUCTS "${header}"
    COMMAND "${CMAKE_COMMAND}" -E make_directory "${include_dir}"
    COMMAND impactgen::impactgen codegen "${problem}" --output "${header}" ${options}
    COMMAND "${CMAKE_COMMAND}" -E touch "${stamp}"
    DEPENDS "${problem}" impactgen::impactgen
    COMMENT "impactgen: generating ${target}.hpp from ${arg_PROBLEM}"
    VERBATIM)
  add_custom_target(${target}_generate DEPENDS "${stamp}")

  # An INTERFACE library's dependencies are followed by whatever links to it,
  # so every consumer is built after the header exists.
  add_library(${target} INTERFACE)
  target_include_directories(${target} INTERFACE "$<BUILD_INTERFACE:${include_dir}>")
  target_compile_features(${target} INTERFACE cxx_std_17)
  add_dependencies(${target} ${target}_generate)
  set_target_properties(${target} PROPERTIES IMPACTGEN_HEADER "${header}")
endfunction()
