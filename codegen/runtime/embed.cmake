# Writes OUTPUT, a C++ source that defines, for each NAME in NAMES (joined by "|"),
#   const char *const impactgen::codegen::NAME
# holding the bytes of DIR/NAME.hpp exactly (no newline added or dropped), for the
# writers to emit verbatim (codegen/runtime.hpp). Run at build time by
# codegen/CMakeLists.txt (cmake -P); no dependency but CMake.
# -D: OUTPUT DIR NAMES
string(REPLACE "|" ";" names "${NAMES}")
set(text "// Written by codegen/runtime/embed.cmake from codegen/runtime/*.hpp: do not edit.\n")
string(APPEND text "#include \"codegen/runtime.hpp\"\n\nnamespace impactgen::codegen\n{\nnamespace\n{\n")
set(defs "")
foreach(name IN LISTS names)
  file(READ ${DIR}/${name}.hpp hex HEX)
  # 16 bytes a line, each as 0xNN, then the terminating 0.
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(REPEAT "0x[0-9a-f][0-9a-f]," 16 line)
  string(REGEX REPLACE "(${line})" "\\1\n    " bytes "${bytes}")
  string(APPEND text "// ${name}.hpp\nconst unsigned char ${name}_bytes[] = {\n    ${bytes}0};\n")
  string(APPEND defs "const char *const ${name} = reinterpret_cast<const char *>(${name}_bytes);\n")
endforeach()
string(APPEND text "} // namespace\n\n${defs}\n} // namespace impactgen::codegen\n")
# Rewritten only when the text changes: no rebuild of the library otherwise.
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUTPUT} "${text}")
endif()
