# config/default.json is the code's defaults, every key present: what
# `stairs-eval --print-config` prints without a config file, byte for byte.
execute_process(COMMAND ${PROGRAM} --print-config OUTPUT_VARIABLE printed RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} --print-config failed (${rc})")
endif()
file(READ ${EXPECTED} shipped)
if(NOT printed STREQUAL shipped)
  message(FATAL_ERROR "${EXPECTED} is not the code's defaults: regenerate it with "
                      "'stairs-eval --print-config > config/default.json'")
endif()
