# Documents handed back to sigmatau are validated (issue 28): a saved adev result for fit, a fit
# result for convert and check, a data sheet. A bad value is exit 2 with the file and the field;
# before, a dev of "abc" dropped the point, -1 and a negative N were used, 1e308 in a sheet
# became inf (PX4) and null (JSON) in the filter files, and 1e999 ended in exit 3.
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
file(WRITE ${documents_dir}/fit_huge_n.json [=[{"channels":[{"name":"gx","quantity":"angular_rate","method":"joint",
 "parameters":{"N":{"value":1e308,"ci_low":1e308,"ci_high":1e308},"B":{"upper_bound":4e-6},"K":{"upper_bound":2e-7}}}]}
]=])
sigmatau_cli_test(NAME cli_documents_fit_negative_n_convert EXIT 2
  STDERR "fit_negative_n\\.json: channels\\[0\\] \\(gx\\)\\.parameters\\.N\\.value: expected a finite number >= 0, got -0\\.0001"
  ARGS convert --fit ${documents_dir}/fit_negative_n.json --rate 100 --to px4)
sigmatau_cli_test(NAME cli_documents_fit_negative_n_check EXIT 2
  STDERR "fit_negative_n\\.json: channels\\[0\\] \\(gx\\)\\.parameters\\.N\\.value: expected a finite number >= 0"
  ARGS check --spec adi_adis16465 ${documents_dir}/fit_negative_n.json)
sigmatau_cli_test(NAME cli_documents_fit_huge_n_px4 EXIT 2
  STDERR "gyro white noise: N = 1e\\+308 rad/s/sqrt\\(Hz\\) gives a variance per sample that is not finite at 100 Hz"
  NO_FILE ${documents_dir}/huge.params
  ARGS convert --fit ${documents_dir}/fit_huge_n.json --rate 100 --to px4 -o ${documents_dir}/huge.params)

file(WRITE ${documents_dir}/huge_sheet.yaml [=[schema: 1
manufacturer: Test
part: T-1
grade: consumer
sources:
  ds:
    document: Test
    kind: secondary
gyro:
  noise_density:
    typ: 1e308 deg/s/sqrt(Hz)
    source: ds
]=])
sigmatau_cli_test(NAME cli_documents_sheet_huge_value EXIT 2
  STDERR "huge_sheet\\.yaml:11:10: gyro\\.noise_density\\.typ: found 1e308 deg/s/sqrt\\(Hz\\), expected a value below 1e\\+100"
  ARGS convert --spec ${documents_dir}/huge_sheet.yaml --rate 200 --to json)
