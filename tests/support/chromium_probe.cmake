# include()d by the checks that lay a page out in headless Chromium (check_report_layout.cmake,
# check_compliance_chart.cmake). Exits 77 (skipped) when Chromium is not installed. Then
# chromium_dump(PROBE WIDTH PROFILE OUT) loads the page PROBE (written by the caller, its probe
# script included) in a window WIDTH px wide, removes PROBE and the profile directory PROFILE,
# and sets OUT to the DOM the browser built (OUT_log to its log); a Chromium failure is fatal.
find_program(CHROMIUM NAMES chromium chromium-browser)
if(NOT CHROMIUM)
  message("SKIPPED: chromium not installed (apt-get install chromium)")
  cmake_language(EXIT 77)
endif()
function(chromium_dump probe width profile out)
  file(REMOVE_RECURSE "${profile}")
  execute_process(
    COMMAND ${CHROMIUM} --headless --no-sandbox --disable-gpu --disable-quic --no-first-run
            --disable-background-networking --disable-component-update --disable-sync
            --user-data-dir=${profile} --hide-scrollbars --window-size=${width},2600
            --virtual-time-budget=3000 --dump-dom "file://${probe}"
    RESULT_VARIABLE code OUTPUT_VARIABLE dom ERROR_VARIABLE log TIMEOUT 120)
  file(REMOVE_RECURSE "${profile}")
  file(REMOVE "${probe}")
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "chromium exited with ${code}:\n${log}")
  endif()
  set(${out} "${dom}" PARENT_SCOPE)
  set(${out}_log "${log}" PARENT_SCOPE)
endfunction()
