# cmake -P: lays out a compliance chart in headless Chromium and checks what a reader sees
# (issue 28: on the ADIS16405 log against the ADIS16448 sheet the long row labels left a plot
# area of about 60 px, the x labels overlapping as "0.512 510", the caption cut at the right).
# FILE is a report.html (its compliance chart, laid out as the report lays it out) or a
# chart's .svg (shown as the report shows it: 100 % of a 1100-px column). In a window WIDTH px
# wide (default 1200) every text of the chart must lie inside the chart, no two texts may
# overlap, and the x labels must spread over at least MIN_SPREAD (default 0.35) of the chart's
# width, so that the plot area is not a strip. MIN_TEXTS: at least this many texts (the rows
# drawn). Exits 77 (skipped) without Chromium, or when FILE is absent and SKIP_IF_ABSENT is set
# (reference data not installed).
include(${CMAKE_CURRENT_LIST_DIR}/chromium_probe.cmake)
if(NOT EXISTS "${FILE}")
  if(SKIP_IF_ABSENT)
    message("SKIPPED: ${FILE} not found")
    cmake_language(EXIT 77)
  endif()
  message(FATAL_ERROR "${FILE} not found")
endif()
if(NOT WIDTH)
  set(WIDTH 1200)
endif()
if(NOT MIN_SPREAD)
  set(MIN_SPREAD 0.35)
endif()
if(NOT MIN_TEXTS)
  set(MIN_TEXTS 1)
endif()
file(READ "${FILE}" page)
if(FILE MATCHES "\\.svg$")
  string(REGEX REPLACE "^<\\?xml[^>]*\\?>" "" page "${page}")
  set(page "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><style>body{margin:0}.plot{width:1100px}.plot svg{width:100%;height:auto}</style></head><body><div class=\"plot\">${page}</div></body></html>")
endif()
get_filename_component(dir "${FILE}" DIRECTORY)
string(RANDOM LENGTH 8 tag)
set(probe "${dir}/compliance_probe_${tag}.html")
file(WRITE "${probe}" "${page}<script>
// The chart is the SVG whose x axis reads 'measured / data-sheet limit'.
const svg = [...document.querySelectorAll('svg')].find(
    s => s.textContent.includes('measured / data-sheet limit'));
const bad = [];
let count = 0;
if (!svg) {
  bad.push('no-chart');
} else {
  const box = svg.getBoundingClientRect();
  const texts = [...svg.querySelectorAll('text')]
      .map(t => ({s: t.textContent.trim(), r: t.getBoundingClientRect()}))
      .filter(t => t.s && t.r.width > 0);
  count = texts.length;
  for (const t of texts) {
    if (t.r.left < box.left - 1 || t.r.right > box.right + 1 || t.r.top < box.top - 1 ||
        t.r.bottom > box.bottom + 1) bad.push('outside:' + t.s);
  }
  for (let i = 0; i < texts.length; ++i) {
    for (let j = i + 1; j < texts.length; ++j) {
      const a = texts[i].r, b = texts[j].r;
      const x = Math.min(a.right, b.right) - Math.max(a.left, b.left);
      const y = Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top);
      if (x > 1 && y > 1) bad.push('overlap:' + texts[i].s + '|' + texts[j].s);
    }
  }
  const ticks = texts.filter(t => /^[0-9.]+$/.test(t.s));
  const spread = ticks.length < 2 ? 0 :
      Math.max(...ticks.map(t => t.r.right)) - Math.min(...ticks.map(t => t.r.left));
  if (spread < ${MIN_SPREAD} * box.width) bad.push('x-labels-span:' + (spread / box.width).toFixed(3));
}
document.body.setAttribute('data-chart', bad.length ? bad.slice(0, 12).join(' ; ') : 'ok');
document.body.setAttribute('data-texts', String(count));
</script>\n")
chromium_dump("${probe}" ${WIDTH} "${dir}/chromium-chart-profile-${tag}" dom)
if(NOT dom MATCHES "data-chart=\"([^\"]*)\"")
  message(FATAL_ERROR "the chart probe did not run in Chromium:\n${dom_log}")
endif()
set(chart "${CMAKE_MATCH_1}")
if(NOT dom MATCHES "data-texts=\"([0-9]+)\"")
  message(FATAL_ERROR "the chart probe did not count the texts")
endif()
set(texts "${CMAKE_MATCH_1}")
if(NOT chart STREQUAL "ok")
  message(FATAL_ERROR "the compliance chart in ${FILE} at ${WIDTH} px: ${chart}")
endif()
if(texts LESS MIN_TEXTS)
  message(FATAL_ERROR "the compliance chart in ${FILE} shows ${texts} texts, expected at least ${MIN_TEXTS}")
endif()
message(STATUS "the compliance chart in ${FILE}: ${texts} texts, inside the chart, none overlapping")
