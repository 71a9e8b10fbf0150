# Embeds a file in the program: writes OUTPUT, a C++ source defining
#   extern const char NAME[];             the bytes of INPUT, then a terminating 0
#   extern const std::size_t NAMESize;    the number of bytes of INPUT (without the 0)
# in namespace NAMESPACE (optional). The bytes are written as hex character literals, so the
# file may hold anything (quotes, backslashes, a raw-string delimiter, NUL, non-ASCII).
# Usage: cmake -DINPUT=page.html -DOUTPUT=page.cpp -DNAME=kPage [-DNAMESPACE=a::b] -P this
foreach(var INPUT OUTPUT NAME)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "embed_resource.cmake: ${var} is required")
  endif()
endforeach()

file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" hex_length)
math(EXPR size "${hex_length} / 2")
# 16 bytes per line: a newline after every 32 hex digits, then each byte as '\xNN'.
string(REPEAT "[0-9a-f]" 32 line_pattern)
string(REGEX REPLACE "(${line_pattern})" "\\1\n" hex "${hex}")
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "'\\\\x\\1', " bytes "${hex}")
string(REGEX REPLACE " \n" "\n  " bytes "${bytes}")

if(DEFINED NAMESPACE AND NOT "${NAMESPACE}" STREQUAL "")
  set(open_namespace "namespace ${NAMESPACE} {\n\n")
  set(close_namespace "\n}  // namespace ${NAMESPACE}\n")
else()
  set(open_namespace "")
  set(close_namespace "")
endif()
get_filename_component(input_name "${INPUT}" NAME)
file(WRITE "${OUTPUT}"
     "// Generated from ${input_name} by embed_resource.cmake; do not edit.\n"
     "#include <cstddef>\n\n"
     "${open_namespace}"
     "extern const char ${NAME}[] = {\n  ${bytes}'\\0'};\n"
     "extern const std::size_t ${NAME}Size = ${size};\n"
     "${close_namespace}")
