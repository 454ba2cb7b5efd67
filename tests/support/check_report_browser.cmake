# cmake -P: load DIR/report.html in headless Chromium (Debian's `chromium`), dump the DOM the
# browser built, and check that the page rendered with its plots (inline SVG elements with
# content) and that the browser logged no JavaScript/console error. Exits 77 (skipped) without
# Chromium.
find_program(CHROMIUM NAMES chromium chromium-browser)
if(NOT CHROMIUM)
  message("SKIPPED: chromium not installed (apt-get install chromium)")
  cmake_language(EXIT 77)
endif()
set(profile "${DIR}/../chromium-profile")
file(REMOVE_RECURSE "${profile}")
execute_process(
  COMMAND ${CHROMIUM} --headless --no-sandbox --disable-gpu --disable-quic --no-first-run
          --disable-background-networking --disable-component-update --disable-sync
          --user-data-dir=${profile} --enable-logging=stderr --v=0
          --virtual-time-budget=5000 --dump-dom "file://${DIR}/report.html"
  RESULT_VARIABLE code OUTPUT_VARIABLE dom ERROR_VARIABLE log TIMEOUT 120)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "chromium exited with ${code}:\n${log}")
endif()
if(log MATCHES "Uncaught|CONSOLE\\([0-9]+\\).*[Ee]rror|net::ERR_")
  message(FATAL_ERROR "the browser reported errors:\n${log}")
endif()
foreach(id plot-adev_gyro plot-psd_gyro plot-adev_accel plot-psd_accel)
  if(NOT dom MATCHES "id=\"${id}\"><svg")
    message(FATAL_ERROR "rendered page lacks the plot ${id}")
  endif()
endforeach()
string(REGEX MATCHALL "<path" paths "${dom}")
list(LENGTH paths npaths)
if(npaths LESS 50)
  message(FATAL_ERROR "the plots hold only ${npaths} paths: they did not render")
endif()
if(NOT dom MATCHES "Data-sheet compliance")
  message(FATAL_ERROR "rendered page lacks the compliance section")
endif()
message(STATUS "report.html rendered in Chromium with ${npaths} SVG paths and no errors")
if(SCREENSHOT)
  execute_process(
    COMMAND ${CHROMIUM} --headless --no-sandbox --disable-gpu --disable-quic --no-first-run
            --disable-background-networking --disable-component-update --disable-sync
            --user-data-dir=${profile} --hide-scrollbars --window-size=1280,2400
            --screenshot=${SCREENSHOT} "file://${DIR}/report.html"
    RESULT_VARIABLE code OUTPUT_QUIET ERROR_QUIET TIMEOUT 120)
endif()
file(REMOVE_RECURSE "${profile}")
