# Runs examples/realtime on the smallest ball at 60 steps a second (PROGRAM) and checks its table:
# ThinTool's row keeps every node out of the plate and the plate out of the ball, and each
# algorithm gets its line on the largest ball that fits the budget.
execute_process(COMMAND ${PROGRAM} --max-faces 128 --rates 60 RESULT_VARIABLE result OUTPUT_VARIABLE output
                ERROR_VARIABLE output)
message(STATUS "${output}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "realtime failed (${result})")
endif()
set(number "[0-9]+(\\.[0-9]+)?")
if(NOT output MATCHES "\\| ThinTool, swept \\(default\\) \\| 128 \\| ${number} \\| ${number} \\| ${number} \\| 0 \\| no \\|")
  message(FATAL_ERROR "realtime: ThinTool's row lets the plate through, or is missing")
endif()
foreach(algorithm "stock E \\(B, skin 0.05\\)" "ThinTool, swept \\(default\\)")
  if(NOT output MATCHES "- ${algorithm}: (128 faces|none of the sizes run)")
    message(FATAL_ERROR "realtime: no line on the largest ball for ${algorithm}")
  endif()
endforeach()
