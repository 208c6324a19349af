# impactgen_generate(): generate a C++ impact solver for your own problem at
# build time, the way flatbuffers_generate_headers() or protobuf_generate() do.
#
#   impactgen_generate(<target>
#                      PROBLEM <file.json>
#                      [NAME <function>]
#                      [NAMESPACE <namespace>]
#                      [PARAMS <symbol>...]
#                      [SET <symbol>=<value>...]
#                      [INVERSE_MASS] [INVERSE_INERTIA] [UNIT_NORMAL]
#                      [JACOBIAN] [WRT <input>...] [ROWS])
#
# Runs, at build time,
#
#   impactgen codegen <file.json> --output <dir>/<target>.hpp --name <function>
#                     [--namespace <namespace>] [--params a,b,c] [--set a=1,b=1/2]
#                     [--inverse-mass] [--inverse-inertia] [--unit-normal]
#                     [--jacobian] [--wrt a,b] [--rows]
#
# and defines an INTERFACE library <target> whose include directory holds
# <target>.hpp, so that
#
#   target_link_libraries(app PRIVATE <target>)
#
# lets app's sources `#include "<target>.hpp"`. The header is regenerated when
# the problem file, the options or the impactgen executable change.
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
#              of the problem must be listed or given a value with SET.
#              Default: all the problem's symbols that SET does not fix, in the
#              order they appear in the problem.
#   SET        exact values of symbols that are not parameters, one item
#              <symbol>=<value> each (SET e=1/2 l=0.3 -> --set e=1/2,l=0.3); the
#              value is a number or an expression, read exactly (0.3 is 3/10).
#              Every item needs a symbol, '=' and a value; no ',' in an item.
#   INVERSE_MASS     option: the mass inputs are inverse masses 1/m (the engine
#                    convention; -> --inverse-mass).
#   INVERSE_INERTIA  option: the inertia inputs of free bodies are inverses, 3-D
#                    tensors I^-1 and planar 1/I (-> --inverse-inertia).
#   UNIT_NORMAL      option: the normal inputs are a unit vector: used as given,
#                    not normalised, checked to have length 1 (-> --unit-normal).
#   JACOBIAN   option: also emit <function>_jacobian, the values and the dense
#              Jacobian d(outputs)/d(inputs), derived exactly (-> --jacobian).
#   WRT        the inputs the Jacobian differentiates by, in this order
#              (WRT vx vy -> --wrt vx,vy); implies JACOBIAN. At least one item.
#              Default (JACOBIAN alone): every input.
#   ROWS       option: also emit <function>_rows, the contact's Jacobian rows,
#              effective masses and restitution bias for an iterative solver
#              (-> --rows).
#
# A malformed item (a SET item without '=', with an empty symbol or value, an
# empty PARAMS or WRT item, a ',' in any item) or a keyword without its values
# stops the configuration with a message naming the keyword.
#
# The generated header is plain C++17 with no dependency, so <target> links to
# nothing. The executable run is the target impactgen::impactgen: the imported
# one of an installed impactgen (find_package(impactgen CONFIG), the full
# package: not COMPONENTS headers alone), or the one built in the same tree.

include_guard(GLOBAL)

function(impactgen_generate target)
  cmake_parse_arguments(PARSE_ARGV 1 arg
    "INVERSE_MASS;INVERSE_INERTIA;UNIT_NORMAL;JACOBIAN;ROWS" "PROBLEM;NAME;NAMESPACE" "PARAMS;SET;WRT")
  set(where "impactgen_generate(${target})")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${where}: unknown arguments: ${arg_UNPARSED_ARGUMENTS} (keywords: PROBLEM NAME NAMESPACE "
                        "PARAMS SET INVERSE_MASS INVERSE_INERTIA UNIT_NORMAL JACOBIAN WRT ROWS)")
  endif()
  if(arg_KEYWORDS_MISSING_VALUES)
    message(FATAL_ERROR "${where}: no value given for ${arg_KEYWORDS_MISSING_VALUES}")
  endif()
  if(NOT DEFINED arg_PROBLEM)
    message(FATAL_ERROR "${where}: PROBLEM <file.json> is required")
  endif()
  if(TARGET ${target})
    message(FATAL_ERROR "${where}: a target named ${target} already exists")
  endif()
  if(NOT TARGET impactgen::impactgen)
    if(TARGET impactgen::headers)
      message(FATAL_ERROR "${where}: only the header-only component of impactgen was found "
                          "(find_package(impactgen ... COMPONENTS headers)); impactgen_generate() needs the full "
                          "package, which has the impactgen executable: request it with "
                          "find_package(impactgen CONFIG REQUIRED) or find_package(impactgen CONFIG REQUIRED COMPONENTS full)")
    endif()
    message(FATAL_ERROR "${where}: the target impactgen::impactgen does not exist; "
                        "call find_package(impactgen CONFIG REQUIRED) first")
  endif()

  # Multi-value keywords become one comma-separated flag value: every item must
  # be non-empty and free of ','. An empty list given explicitly (WRT "") counts
  # as no value.
  foreach(keyword IN ITEMS PARAMS SET WRT)
    if(DEFINED arg_${keyword} AND arg_${keyword} STREQUAL "")
      message(FATAL_ERROR "${where}: no value given for ${keyword}")
    endif()
    foreach(item IN LISTS arg_${keyword})
      if(item STREQUAL "")
        message(FATAL_ERROR "${where}: an empty item in ${keyword}")
      endif()
      if(item MATCHES ",")
        message(FATAL_ERROR "${where}: ${keyword} item '${item}' contains ',': give one item per value "
                            "(${keyword} a b, not ${keyword} a,b)")
      endif()
    endforeach()
  endforeach()
  # SET items as <symbol>=<value>, blanks around either part dropped.
  set(set_symbols "")
  set(set_items "")
  foreach(item IN LISTS arg_SET)
    if(NOT item MATCHES "^([^=]*)=(.*)$")
      message(FATAL_ERROR "${where}: SET item '${item}' is not <symbol>=<value> (no '=')")
    endif()
    string(STRIP "${CMAKE_MATCH_1}" symbol)
    string(STRIP "${CMAKE_MATCH_2}" value)
    if(symbol STREQUAL "")
      message(FATAL_ERROR "${where}: SET item '${item}' has no symbol before '=' (write <symbol>=<value>)")
    endif()
    if(value STREQUAL "")
      message(FATAL_ERROR "${where}: SET item '${item}' has an empty value (write <symbol>=<value>)")
    endif()
    if(symbol IN_LIST set_symbols)
      message(FATAL_ERROR "${where}: SET gives the symbol '${symbol}' twice")
    endif()
    list(APPEND set_symbols "${symbol}")
    list(APPEND set_items "${symbol}=${value}")
  endforeach()

  get_filename_component(problem "${arg_PROBLEM}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  get_source_file_property(problem_is_generated "${problem}" GENERATED)
  if(NOT EXISTS "${problem}" AND NOT problem_is_generated)
    message(FATAL_ERROR "impactgen_generate(${target}): problem file ${problem} does not exist")
  endif()

  if(DEFINED arg_NAME)
    set(function_name "${arg_NAME}")
  else()
    string(MAKE_C_IDENTIFIER "${target}" function_name)
  endif()

  set(include_dir "${CMAKE_CURRENT_BINARY_DIR}/impactgen/${target}")
  set(header "${include_dir}/${target}.hpp")

  set(options --name "${function_name}")
  if(DEFINED arg_NAMESPACE)
    list(APPEND options --namespace "${arg_NAMESPACE}")
  endif()
  if(DEFINED arg_PARAMS)
    list(JOIN arg_PARAMS "," params)
    list(APPEND options --params "${params}")
  endif()
  if(NOT set_items STREQUAL "")
    list(JOIN set_items "," values)
    list(APPEND options --set "${values}")
  endif()
  if(arg_INVERSE_MASS)
    list(APPEND options --inverse-mass)
  endif()
  if(arg_INVERSE_INERTIA)
    list(APPEND options --inverse-inertia)
  endif()
  if(arg_UNIT_NORMAL)
    list(APPEND options --unit-normal)
  endif()
  if(arg_JACOBIAN OR DEFINED arg_WRT)
    list(APPEND options --jacobian)
  endif()
  if(DEFINED arg_WRT)
    list(JOIN arg_WRT "," wrt)
    list(APPEND options --wrt "${wrt}")
  endif()
  if(arg_ROWS)
    list(APPEND options --rows)
  endif()

  # The options as a file rewritten only when they change: the rule depends on
  # it, so that a changed keyword regenerates the header with every generator
  # (Makefiles do not compare command lines).
  set(options_file "${CMAKE_CURRENT_BINARY_DIR}/impactgen/${target}.options")
  list(JOIN options "\n" options_text)
  set(previous_options "")
  if(EXISTS "${options_file}")
    file(READ "${options_file}" previous_options)
  endif()
  if(NOT previous_options STREQUAL "${options_text}\n")
    file(WRITE "${options_file}" "${options_text}\n")
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
    COMMAND impactgen::impactgen --time-limit 0 codegen "${problem}" --output "${header}" ${options}
    COMMAND "${CMAKE_COMMAND}" -E touch "${stamp}"
    DEPENDS "${problem}" "${options_file}" impactgen::impactgen
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
