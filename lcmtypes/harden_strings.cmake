# Run after lcm-gen (cmake -P): lcm-gen's C++ decoders check a string's encoded
# length only against the bytes left, so a negative length passes; INT_MIN then
# overflows "len - 1" to INT_MAX and the string copies 2 GB out of a message of
# a hundred bytes (found by fuzzing, tests/fuzz/corpus/*/string_length_int_min).
# Every string length must be at least 1 (it counts the terminating NUL).
#   cmake -DDIR=<generated cpp dir> -P harden_strings.cmake
file(GLOB headers "${DIR}/stairs/*.hpp")
foreach(h ${headers})
  file(READ "${h}" text)
  string(REGEX REPLACE "if\\(([_a-zA-Z0-9]+) > maxlen - pos\\) return -1;"
         "if(\\1 < 1 || \\1 > maxlen - pos) return -1;" hardened "${text}")
  if(NOT hardened STREQUAL text)
    file(WRITE "${h}" "${hardened}")
  endif()
endforeach()
