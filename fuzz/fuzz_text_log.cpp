// libFuzzer harness: the text log reader (CSV / TSV / whitespace, gzip) with options chosen by
// the first byte: time column, time unit, gap and non-finite policies, a tiny read buffer (rows
// split across buffer boundaries; else 4 KiB, not the 4 MiB default, whose zeroing per input under
// ASan took most of the time).
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sigmatau;
  if (size < 1) return 0;
  const std::uint8_t flags = data[0];
  fuzz::write_scratch(data + 1, size - 1);
  LogOptions o;
  o.path = fuzz::scratch_path();
  if (flags & 1) o.time_column = "0";
  o.time_unit = static_cast<TimeUnit>((flags >> 1) & 3);
  o.gaps = static_cast<GapPolicy>((flags >> 3) & 3);
  o.nonfinite = (flags & 32) ? NonFinitePolicy::skip_row : NonFinitePolicy::error;
  o.read_buffer_bytes = (flags & 64) ? 5 : 4096;
  if (flags & 128) o.columns = {"1"};
  fuzz::read_all(o);
  return 0;
}
