# cmake -P: lays out DIR/report.html in headless Chromium at a window WIDTH px wide (default
# 1200) with every <details> open, and checks that nothing is cut off or hidden sideways: no
# element scrolls horizontally (its content wider than its box) and none reaches past the
# window's right edge (review F, finding 15: the filter arithmetic scrolled sideways and the end
# of its long lines was not on screen). A probe script is appended to a copy of the page (the
# report itself has none); its finding is read from the DOM Chromium dumps. Exits 77 (skipped)
# without Chromium.
include(${CMAKE_CURRENT_LIST_DIR}/chromium_probe.cmake)
if(NOT WIDTH)
  set(WIDTH 1200)
endif()
file(READ "${DIR}/report.html" html)
set(probe "${DIR}/../layout_probe.html")
file(WRITE "${probe}" "${html}<script>
for (const d of document.querySelectorAll('details')) d.open = true;
const limit = document.documentElement.clientWidth;
const name = e => e.tagName.toLowerCase() + (e.id ? '#' + e.id : '') + (e.className && typeof e.className === 'string' ? '.' + e.className.replace(/ /g, '.') : '');
const bad = [];
for (const e of document.querySelectorAll('body *')) {
  if (e.closest('svg') && e.tagName.toLowerCase() !== 'svg') continue;
  const style = getComputedStyle(e);
  if (style.overflowX !== 'visible' && e.scrollWidth > e.clientWidth + 1) bad.push('scrolls:' + name(e));
  if (e.getBoundingClientRect().right > limit + 1) bad.push('past-edge:' + name(e));
}
if (document.documentElement.scrollWidth > limit + 1) bad.push('page-wider-than-window');
document.body.setAttribute('data-layout', bad.length ? bad.slice(0, 20).join(' ') : 'ok');
document.body.setAttribute('data-files', String(document.querySelectorAll('details.file').length));
</script>\n")
chromium_dump("${probe}" ${WIDTH} "${DIR}/../chromium-layout-profile" dom)
if(NOT dom MATCHES "data-layout=\"([^\"]*)\"")
  message(FATAL_ERROR "the layout probe did not run in Chromium:\n${dom_log}")
endif()
set(layout "${CMAKE_MATCH_1}")
if(NOT layout STREQUAL "ok")
  message(FATAL_ERROR "report.html at ${WIDTH} px hides content sideways: ${layout}")
endif()
if(NOT dom MATCHES "data-files=\"([0-9]+)\"")
  message(FATAL_ERROR "the layout probe did not count the filter files")
endif()
if(MIN_FILES AND CMAKE_MATCH_1 LESS MIN_FILES)
  message(FATAL_ERROR "report.html shows ${CMAKE_MATCH_1} filter files, expected at least ${MIN_FILES}")
endif()
message(STATUS "report.html at ${WIDTH} px: nothing cut off sideways, ${CMAKE_MATCH_1} filter files open")
