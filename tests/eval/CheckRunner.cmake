# Runs thintool_run as a user would: a two-value sweep of the sheet scene writes a CSV and a JSON
# file with a row per run; a scene file with a misspelt field fails with the file, line, field and
# the names it expected.
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT}/steps)
execute_process(
  COMMAND ${RUNNER} --quiet ${SCENES}/sheet_pierce.json --sweep algorithm=paper,swept
          --csv ${OUT}/rows.csv --json ${OUT}/rows.json --steps ${OUT}/steps
  RESULT_VARIABLE status OUTPUT_VARIABLE table ERROR_VARIABLE errors)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the sweep failed (${status}): ${errors}")
endif()
file(STRINGS ${OUT}/rows.csv rows)
list(LENGTH rows count)
if(NOT count EQUAL 3)
  message(FATAL_ERROR "expected a header and 2 rows, found ${count} lines: ${rows}")
endif()
list(GET rows 1 paper)
list(GET rows 2 swept)
if(NOT paper MATCHES "^sheet_pierce,.*,paper,paper," OR NOT swept MATCHES "^sheet_pierce,.*,swept,swept,")
  message(FATAL_ERROR "rows out of order: ${rows}")
endif()
file(READ ${OUT}/rows.json json)
string(JSON runs LENGTH "${json}")
string(JSON crossed GET "${json}" 1 crossed_nodes)
if(NOT runs EQUAL 2 OR NOT crossed EQUAL 0)
  message(FATAL_ERROR "the JSON rows are wrong: ${json}")
endif()
if(NOT EXISTS ${OUT}/steps/run0.csv OR NOT EXISTS ${OUT}/steps/run1.csv)
  message(FATAL_ERROR "no per-step CSV")
endif()
if(NOT table MATCHES "\\| sheet_pierce \\| swept \\| 1/60 \\|")
  message(FATAL_ERROR "the markdown table is wrong: ${table}")
endif()

file(READ ${SCENES}/sheet_pierce.json scene)
string(REPLACE "\"speed\": 10" "\"sped\": 10" scene "${scene}")
file(WRITE ${OUT}/bad.json "${scene}")
execute_process(COMMAND ${RUNNER} --quiet ${OUT}/bad.json RESULT_VARIABLE status ERROR_VARIABLE errors)
if(NOT status EQUAL 1 OR NOT errors MATCHES "bad.json:[0-9]+:[0-9]+: tools\\[0\\]\\.trajectory: .*sped.*speed")
  message(FATAL_ERROR "a misspelt field gave status ${status} and: ${errors}")
endif()

# The study's report on a small matrix of its own: two algorithms at two speeds.
if(PYTHON)
  file(MAKE_DIRECTORY ${OUT}/study)
  execute_process(
    COMMAND ${RUNNER} --quiet ${SCENES}/plate_press.json --set thintool.force=true
            --sweep algorithm=stock-E,swept --sweep tools[0].trajectory.speed=1,5
            --reference step.dt=1/240 --reference algorithm=swept --csv ${OUT}/study/plate_press-matrix.csv
    RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE errors)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "the small matrix failed (${status}): ${errors}")
  endif()
  execute_process(COMMAND ${PYTHON} ${REPORT} ${OUT}/study ${OUT}/study.md RESULT_VARIABLE status ERROR_VARIABLE errors)
  file(READ ${OUT}/study.md report)
  if(NOT status EQUAL 0 OR NOT report MATCHES "\\| plate \\| ThinTool, swept \\(default\\) \\| 0 of 2 \\| 0 \\| 0 \\|"
     OR NOT report MATCHES "\\| plate \\| stock E \\(B, skin 0.05\\) \\| [12] of 2 \\|")
    message(FATAL_ERROR "the study report (${status}): ${errors}\n${report}")
  endif()
endif()
