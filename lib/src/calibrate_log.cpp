// A calibration log in memory up to a budget, beyond it in an unlinked temporary file
// (calibrate_log.hpp); and the two kinds of samples the calibration reads (calibrate_internal.hpp).
#include "sigmatau/calibrate_log.hpp"

#include <algorithm>
#include <optional>
#include <vector>

#include "analysis_spill.hpp"
#include "calibrate_internal.hpp"
#include "phase_spill.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {

struct CalibrationLog::Impl {
  bool gyro = false, temperature = false;
  int channels = 3;
  std::int64_t memory_bytes = 0;
  std::string directory;
  std::int64_t rows = 0;
  /// In memory: pieces of kPieceRows rows each (the last one filling), so growing never copies.
  std::vector<std::vector<double>> pieces;
  std::optional<detail::ValueSpill> spill;

  std::int64_t piece_values() const { return kPieceRows * channels; }

  void move_to_file() {
    spill.emplace(directory);
    directory = detail::temporary_directory(directory);
    for (auto& piece : pieces) {
      spill->append(piece);
      std::vector<double>().swap(piece);
    }
    pieces.clear();
    pieces.shrink_to_fit();
  }
};

CalibrationLog::CalibrationLog(bool gyro, bool temperature, std::int64_t memory_bytes,
                               const std::string& directory)
    : impl_(std::make_unique<Impl>()) {
  impl_->gyro = gyro;
  impl_->temperature = temperature;
  impl_->channels = 3 + (gyro ? 3 : 0) + (temperature ? 1 : 0);
  impl_->memory_bytes = memory_bytes;
  impl_->directory = directory;
}

CalibrationLog::~CalibrationLog() = default;

int CalibrationLog::channels() const { return impl_->channels; }
bool CalibrationLog::has_gyro() const { return impl_->gyro; }
bool CalibrationLog::has_temperature() const { return impl_->temperature; }
std::int64_t CalibrationLog::rows() const { return impl_->rows; }
bool CalibrationLog::spilled() const { return impl_->spill.has_value(); }
const std::string& CalibrationLog::directory() const { return impl_->directory; }

void CalibrationLog::append(std::span<const double> values) {
  Impl& m = *impl_;
  const auto c = static_cast<std::size_t>(m.channels);
  if (values.size() % c != 0)
    throw Error("internal: calibration rows of " + std::to_string(c) + " values, got " +
                std::to_string(values.size()));
  m.rows += static_cast<std::int64_t>(values.size() / c);
  while (!values.empty()) {
    if (m.spill) {
      m.spill->append(values);
      return;
    }
    if (m.pieces.empty() || static_cast<std::int64_t>(m.pieces.back().size()) == m.piece_values()) {
      const auto held = static_cast<std::int64_t>(m.pieces.size()) * m.piece_values() * 8;
      if (held + m.piece_values() * 8 > m.memory_bytes) {
        m.move_to_file();
        continue;
      }
      m.pieces.emplace_back();
      m.pieces.back().reserve(static_cast<std::size_t>(m.piece_values()));
    }
    auto& piece = m.pieces.back();
    const std::size_t take =
        std::min(values.size(), static_cast<std::size_t>(m.piece_values()) - piece.size());
    piece.insert(piece.end(), values.begin(), values.begin() + static_cast<std::ptrdiff_t>(take));
    values = values.subspan(take);
  }
}

void CalibrationLog::read(
    std::int64_t begin, std::int64_t end,
    const std::function<void(std::int64_t, std::int64_t, const double*)>& each) const {
  Impl& m = *impl_;  // the file's write buffer is flushed before reading
  if (begin < 0 || end > m.rows || begin > end)
    throw Error("internal: rows [" + std::to_string(begin) + ", " + std::to_string(end) +
                ") outside the calibration log's " + std::to_string(m.rows));
  const std::int64_t c = m.channels;
  if (m.spill) {
    m.spill->flush();
    // One for_each call per group of rows that fits its piece size, so no row is split.
    const std::int64_t step = detail::ValueSpill::kReadValues / c;
    for (std::int64_t r = begin; r < end;) {
      const std::int64_t n = std::min(step, end - r);
      m.spill->for_each(r * c, (r + n) * c,
                        [&](std::span<const double> values) { each(r, n, values.data()); });
      r += n;
    }
    return;
  }
  for (std::int64_t r = begin; r < end;) {
    const std::int64_t piece = r / kPieceRows, offset = r % kPieceRows;
    const std::int64_t n = std::min(kPieceRows - offset, end - r);
    each(r, n, m.pieces[static_cast<std::size_t>(piece)].data() + offset * c);
    r += n;
  }
}

CalibrationResult calibrate(const CalibrationLog& log, double rate_hz, bool increments,
                            const CalibrationOptions& options) {
  return detail::calibrate_samples(detail::LogSamples(log, rate_hz, increments), options);
}

namespace detail {

InputSamples::InputSamples(const CalibrationInput& input) : in_(input) {
  const std::size_t n = in_.accel[0].size();
  const auto check = [&](const std::array<std::vector<double>, 3>& x, const char* what) {
    for (const auto& v : x)
      if (v.size() != n)
        throw Error(std::string("calibrate: the ") + what + " channels must all have " +
                    std::to_string(n) + " samples");
  };
  check(in_.accel, "accelerometer");
  if (has_gyro()) check(in_.gyro, "gyroscope");
  if (has_temperature() && in_.temperature_k.size() != n)
    throw Error("calibrate: the temperature column must have one value per sample");
}

std::int64_t InputSamples::rows() const { return static_cast<std::int64_t>(in_.accel[0].size()); }

void InputSamples::for_each(std::int64_t begin, std::int64_t end,
                            const std::function<void(const SampleRows&)>& each) const {
  if (begin >= end) return;
  SampleRows rows;
  rows.first = begin;
  rows.count = end - begin;
  const auto at = [&](const std::vector<double>& v) { return v.data() + begin; };
  for (int a = 0; a < 3; ++a) {
    rows.column[static_cast<std::size_t>(kAccelChannel + a)] =
        at(in_.accel[static_cast<std::size_t>(a)]);
    if (has_gyro())
      rows.column[static_cast<std::size_t>(kGyroChannel + a)] =
          at(in_.gyro[static_cast<std::size_t>(a)]);
  }
  if (has_temperature()) rows.column[kTemperatureChannel] = at(in_.temperature_k);
  each(rows);
}

void LogSamples::for_each(std::int64_t begin, std::int64_t end,
                          const std::function<void(const SampleRows&)>& each) const {
  const int c = log_.channels();
  log_.read(begin, end, [&](std::int64_t first, std::int64_t n, const double* values) {
    SampleRows rows;
    rows.first = first;
    rows.count = n;
    rows.stride = c;
    for (int a = 0; a < 3; ++a) {
      rows.column[static_cast<std::size_t>(kAccelChannel + a)] = values + a;
      if (log_.has_gyro()) rows.column[static_cast<std::size_t>(kGyroChannel + a)] = values + 3 + a;
    }
    if (log_.has_temperature()) rows.column[kTemperatureChannel] = values + c - 1;
    each(rows);
  });
}

}  // namespace detail
}  // namespace sigmatau
