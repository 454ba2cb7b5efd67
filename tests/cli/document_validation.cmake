# Documents handed back to sigmatau are validated (issue 28): a saved adev result for fit, a fit
# result for convert and check. A bad value is exit 2 with the file and the field; before, a
# dev of "abc" dropped the point, -1 and a negative N were used, and 1e999 ended in exit 3.
set(documents_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_documents)
file(MAKE_DIRECTORY ${documents_dir})
set(adev_doc_head [=[{"input":{"rate_hz":10,"samples":2000,"kind":"rate"},"results":[{"channel":"gx","statistic":"oadev","unit":"deg/s","points":[]=])
set(adev_doc_tail [=[]}]}]=])
set(adev_points "")
foreach(m 1 2 4 8 16 32 64 128)
  math(EXPR whole "${m} / 10")  # tau = m / 10 Hz, written as WHOLE.TENTHS
  math(EXPR tenths "${m} % 10")
  if(m EQUAL 4)
    set(dev "DEV")
  else()
    set(dev "0.0${m}")
  endif()
  string(APPEND adev_points "{\"tau\":${whole}.${tenths},\"m\":${m},\"n\":1000,\"dev\":${dev},\"edf\":100,\"alpha\":0},")
endforeach()
string(REGEX REPLACE ",$" "" adev_points "${adev_points}")
foreach(case abc:"abc" negative:-1 overflow:1e999)
  string(REPLACE ":" ";" pair "${case}")
  list(GET pair 0 name)
  list(GET pair 1 value)
  string(REPLACE "DEV" "${value}" points "${adev_points}")
  file(WRITE ${documents_dir}/adev_${name}.json "${adev_doc_head}${points}${adev_doc_tail}\n")
endforeach()
sigmatau_cli_test(NAME cli_documents_adev_dev_text EXIT 2
  STDERR "adev_abc\\.json: results\\[0\\]\\.points\\[2\\]\\.dev: expected a finite number >= 0, got \"abc\""
  ARGS fit ${documents_dir}/adev_abc.json)
sigmatau_cli_test(NAME cli_documents_adev_dev_negative EXIT 2
  STDERR "adev_negative\\.json: results\\[0\\]\\.points\\[2\\]\\.dev: expected a finite number >= 0, got -1"
  ARGS fit ${documents_dir}/adev_negative.json)
sigmatau_cli_test(NAME cli_documents_adev_dev_overflow EXIT 2
  STDERR "adev_overflow\\.json: not valid JSON \\(.*number overflow"
  ARGS fit ${documents_dir}/adev_overflow.json)

file(WRITE ${documents_dir}/fit_negative_n.json [=[{"channels":[{"name":"gx","quantity":"angular_rate","method":"joint",
 "parameters":{"N":{"value":-1e-4,"ci_low":9e-5,"ci_high":1.1e-4},"B":{"upper_bound":4e-6},"K":{"upper_bound":2e-7}}}]}
]=])
sigmatau_cli_test(NAME cli_documents_fit_negative_n_convert EXIT 2
  STDERR "fit_negative_n\\.json: channels\\[0\\] \\(gx\\)\\.parameters\\.N\\.value: expected a finite number >= 0, got -0\\.0001"
  ARGS convert --fit ${documents_dir}/fit_negative_n.json --rate 100 --to px4)
sigmatau_cli_test(NAME cli_documents_fit_negative_n_check EXIT 2
  STDERR "fit_negative_n\\.json: channels\\[0\\] \\(gx\\)\\.parameters\\.N\\.value: expected a finite number >= 0"
  ARGS check --spec adi_adis16465 ${documents_dir}/fit_negative_n.json)
