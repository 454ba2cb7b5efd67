#pragma once
/// \file calibrate_log.hpp
/// A calibration log in bounded memory: the rows are appended once, as they are read, and read
/// back as often as the calibration needs (it makes about five passes: the detector's window
/// statistic and its exact 25th percentile, the static intervals' means, their covariances, the
/// gyroscope over the rotations). The rows stay in memory up to a budget; beyond it they move
/// to an unlinked temporary file (freed by the kernel however the process ends) and are read
/// back with pread in small pieces, so the resident memory stays about the budget whatever the
/// log's length. The values are stored as doubles, so a spilled log gives the same calibration
/// to the last bit.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include "sigmatau/calibrate.hpp"

namespace sigmatau {

class CalibrationLog {
 public:
  /// A log of rows ax, ay, az [, gx, gy, gz] [, temperature] (in SI: m/s^2 and rad/s, or m/s
  /// and rad per sample for increments; temperature in K). `memory_bytes` bounds the rows kept
  /// in memory; `directory` holds the temporary file (empty: $TMPDIR, else /tmp).
  CalibrationLog(bool gyro, bool temperature, std::int64_t memory_bytes,
                 const std::string& directory = "");
  ~CalibrationLog();
  CalibrationLog(const CalibrationLog&) = delete;
  CalibrationLog& operator=(const CalibrationLog&) = delete;

  /// Values per row: 3, 6 (with gyro) or 4 / 7 (with temperature).
  int channels() const;
  bool has_gyro() const;
  bool has_temperature() const;

  /// Appends rows given row by row (`values.size()` a multiple of channels(), in the order
  /// above). Throws Error when the temporary file cannot be created or written (disk full).
  void append(std::span<const double> values);
  /// Rows appended so far.
  std::int64_t rows() const;
  /// Whether the rows went to the temporary file (the memory budget was exceeded).
  bool spilled() const;
  /// The temporary file's directory (meaningful once spilled()).
  const std::string& directory() const;

  /// Calls each(first_row, rows, values) on consecutive pieces covering rows [begin, end),
  /// `values` row by row (channels() per row). Throws Error on a read error of the file.
  void read(std::int64_t begin, std::int64_t end,
            const std::function<void(std::int64_t, std::int64_t, const double*)>& each) const;

  /// Rows per piece in memory and per read of the file (65536).
  static constexpr std::int64_t kPieceRows = 65536;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// calibrate() on a CalibrationLog sampled at `rate_hz` [Hz], holding increments per sample when
/// `increments`. Same results as calibrate() on the same values as a CalibrationInput, in memory
/// independent of the log's length beyond the log's own budget (the detector holds two 8 MiB
/// histograms and at most 2^21 candidates per sensor; the gyroscope fit its integration steps up
/// to options.rotation_memory_bytes). Throws like calibrate().
CalibrationResult calibrate(const CalibrationLog& log, double rate_hz, bool increments,
                            const CalibrationOptions& options);

}  // namespace sigmatau
