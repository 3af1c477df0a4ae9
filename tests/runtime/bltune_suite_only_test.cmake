# `bltune --suite DIR --only X` keeps the suite's layout (OUT/<scene>/, even when X leaves one scene)
# and rebuilds OUT/summary.csv over every OUT/<scene>/result.json, so scenes retuned one at a time
# replace their own row and keep the others'.
# -DBLTUNE= -DSUITE= -DWORK=
file(REMOVE_RECURSE ${WORK})
set(args --suite ${SUITE} --image 12 --truth-samples 4 --rules none,box --population 4 --generations 1
         --restarts 1 --pixels 60 --nm-evals 0 --max-points 2 --cache ${WORK}/cache --jit-cache ${WORK}/jit
         --cost-model ${WORK}/cost_model.json --calibration evaluator --out ${WORK}/out)
foreach(scene checkerboard_none bricks_none)
  execute_process(COMMAND ${BLTUNE} ${args} --only ${scene} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "bltune --only ${scene} failed (${rc}):\n${out}")
  endif()
  if(NOT EXISTS ${WORK}/out/${scene}/report.md)
    message(FATAL_ERROR "--suite --only ${scene} wrote no ${WORK}/out/${scene}/report.md:\n${out}")
  endif()
endforeach()
if(EXISTS ${WORK}/out/report.md)
  message(FATAL_ERROR "--suite --only wrote a scene's report into the suite directory itself")
endif()
file(STRINGS ${WORK}/out/summary.csv rows)
list(LENGTH rows n)
string(FIND "${rows}" "checkerboard_none," a)
string(FIND "${rows}" "bricks_none," b)
if(NOT n EQUAL 3 OR a EQUAL -1 OR b EQUAL -1)
  message(FATAL_ERROR "summary.csv should hold a header and both scenes' rows, got:\n${rows}")
endif()
