#pragma once
// `sigmatau psd` reading: the Welch PSD of every channel of a log, fed segment by segment, so
// that memory is bounded by the segments and not by the log's length.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "log_options.hpp"
#include "sigmatau/psd.hpp"

namespace sigmatau::cli {

/// The PSDs of a log and what was read.
struct LogPsd {
  LoadedChannels input;          ///< path, channel names, timing, rate, kind and unit (no samples)
  std::vector<PsdCurve> curves;  ///< per channel: PSD of the rate series (SI with --unit)
  /// Per channel: its value when every sample is the same (a stuck sensor, or precision lost),
  /// in the input unit; nullopt otherwise (runs as check_stuck finds them).
  std::vector<std::optional<double>> constant_value;
  /// The outlier warnings of the channels (the check analyze runs: outlier_warnings.hpp), in
  /// channel order; the same whether the log was read into memory or block by block.
  std::vector<std::string> outlier_warnings;
};

/// Welch PSD (`welch`; segment_length 0 = default_segment_length of the rate series' length) of
/// the rate series of every channel: increments x rate, phase differenced x rate. The numbers
/// are those of welch_psd on the whole series in memory, bit for bit (same segments). How:
/// - --gaps fill and split need the whole log (fill_gaps; the segments, Welch windows inside
///   one): read into memory as before.
/// - Otherwise the log is read block by block into a WelchAccumulator per channel. Until the
///   segment length is known the blocks are held, at most `memory_bytes` of them: the length is
///   known from --segment, from the row count the input states (a raw binary file's size, a ROS
///   bag's index or summary for the topic picked without --topic), from the log ending within
///   the held blocks, or from the held rows reaching the count at which the default length stops
///   growing (2^23 samples gives 2^20). When the held blocks exceed `memory_bytes` first, a file
///   is counted in a first read pass; a pipe is an Error asking for --segment.
/// - A row count stated up front is checked at the end (rows skipped by --nonfinite skip may
///   change the default length); when it led to another length, the file is read again.
/// - A rate from the time column is final after its first 100001 stamps (TimingReport): those
///   rows are always held.
/// Every value read also goes through the outlier check (LogPsd::outlier_warnings).
/// The notes on stderr (note_reading) and the progress line are those of load_channels.
LogPsd log_psd(const LogArguments& args, const WelchOptions& welch, std::int64_t memory_bytes);

}  // namespace sigmatau::cli
