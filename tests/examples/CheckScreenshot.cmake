# Runs an example's screenshot mode under a virtual display and checks that a PNG of some size
# came out (the content is checked by thintool_viewer_tests).
file(REMOVE ${OUT})
execute_process(COMMAND ${XVFB} -a -s "-screen 0 1280x720x24 -noreset" ${EXAMPLE} --screenshot ${OUT} --after 30
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
message(STATUS "${output}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the screenshot run failed (${result})")
endif()
file(SIZE ${OUT} size)
if(size LESS 10000)
  message(FATAL_ERROR "the screenshot is missing or blank (${size} bytes)")
endif()
