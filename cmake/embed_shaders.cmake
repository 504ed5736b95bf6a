# Writes OUTPUT, a C++ source defining sluice::render::shader_source(name), with the
# text of every shaders/*.glsl file as a raw string literal, so the binary needs no
# shader files at run time. Run as: cmake -DOUTPUT=... -DSHADERS="a;b" -P this file.
set(body "// Generated from shaders/*.glsl by cmake/embed_shaders.cmake; do not edit.\n")
string(APPEND body "#include <cstring>\n\nnamespace sluice::render {\n\n")
string(APPEND body "const char* shader_source(const char* name) {\n")
foreach(file IN LISTS SHADERS)
  get_filename_component(name "${file}" NAME)
  file(READ "${file}" text)
  string(FIND "${text}" ")glsl\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} contains the raw-string delimiter )glsl\"")
  endif()
  string(APPEND body "  if (std::strcmp(name, \"${name}\") == 0) return R\"glsl(${text})glsl\";\n")
endforeach()
string(APPEND body "  return nullptr;\n}\n\n}  // namespace sluice::render\n")
# Only touch the file when its text changes, so unchanged shaders do not rebuild.
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
  if(old STREQUAL body)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${body}")
