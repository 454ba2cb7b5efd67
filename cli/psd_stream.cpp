#include "psd_stream.hpp"

#include "channel_units.hpp"
#include "outlier_warnings.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <system_error>
#include <utility>

#include "sigmatau/allan_segments.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/psd.hpp"
#include "sigmatau/rate_series.hpp"

namespace sigmatau::cli {
namespace {

/// Stamps after which TimingReport::rate_hz is final (log_reader.hpp, TimingReport).
constexpr std::int64_t kRateStamps = kRateMedianIntervals + 1;

/// Read passes at most (the first, a count of rows, one more when a stated count was wrong):
/// a file that keeps changing length between passes is an Error rather than a loop.
constexpr int kMaxPasses = 3;

/// Whether the input can be read a second time (a file or a rosbag2 folder, not a pipe).
bool rereadable(const std::string& path) {
  if (path == "-") return false;
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) || std::filesystem::is_directory(path, ec);
}

/// Rows the input says it holds before it is read, -1 when it does not: a raw binary file
/// (uncompressed) from its size, a ROS bag read without --topic from its index or summary.
std::int64_t stated_rows(const LogOptions& options, const TimingReport& opened) {
  if (!opened.bag_topic.empty()) {
    for (const BagTopic& topic : opened.bag_topics) {
      if (topic.name == opened.bag_topic) return topic.messages;
    }
    return -1;
  }
  if (options.binary == BinaryFormat::none || !rereadable(options.path)) return -1;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(options.path, ec) || is_gzip_file(options.path)) return -1;
  const auto bytes = static_cast<std::int64_t>(std::filesystem::file_size(options.path, ec));
  if (ec) return -1;
  return std::max<std::int64_t>(0, bytes - options.skip_bytes) /
         (value_bytes(options.binary) * options.binary_channels);
}

/// Rows of the input, read through once (a counting pass).
std::int64_t count_rows(const LogOptions& options) {
  LogReader reader(options);
  SampleBlock block;
  Progress progress;
  while (reader.read_block(block)) progress.update(reader.bytes_read(), reader.total_bytes());
  progress.finish();
  return reader.timing().samples;
}

/// The rate series of one channel, fed to its Welch accumulator with the arithmetic of the
/// in-memory path (value x to_si, then increment x rate or (x[i+1] - x[i]) x rate). The values
/// as read also go through a RunChecker, to tell a constant channel; `values` are left scaled
/// (x to_si), as load_channels holds them.
class ChannelFeed {
 public:
  ChannelFeed(std::string name, double rate_hz, const WelchOptions& welch, DataKind kind,
              double to_si)
      : accumulator_(rate_hz, welch), rates_(kind, rate_hz), to_si_(to_si), runs_(std::move(name)) {}

  void add(std::vector<double>& values) {
    runs_.add(values);
    rows_ += static_cast<std::int64_t>(values.size());
    if (to_si_ != 1.0) {
      for (double& v : values) v *= to_si_;
    }
    accumulator_.add(rates_.convert(values));
  }

  PsdCurve result() const { return accumulator_.result(); }

  /// The value of a constant channel (as read), nullopt otherwise. Call once, at the end.
  std::optional<double> constant_value() { return whole_run_value(runs_.finish(), rows_); }

 private:
  WelchAccumulator accumulator_;
  RateStream rates_;
  double to_si_;
  RunChecker runs_;
  std::int64_t rows_ = 0;
};

/// f(), with an Error it throws (a PSD beyond the range of a double) naming the input and the
/// channel.
template <class F>
PsdCurve for_channel(const std::string& input, const std::string& channel, F&& f) {
  try {
    return f();
  } catch (const ParseError&) {
    throw;
  } catch (const Error& e) {
    throw Error((input == "-" ? std::string("<stdin>") : input) + ": channel \"" + channel +
                "\": " + e.what());
  }
}

void check_phase_length(DataKind kind, std::int64_t rows) {
  if (kind == DataKind::phase && rows < 2) throw Error("phase input needs at least two samples");
}

/// --gaps fill and split: the whole log in memory (fill_gaps, or the segments the reader found),
/// then welch_psd per channel; with split segments, Welch windows stay inside one segment
/// (welch_psd_stretches), as in analyze.
LogPsd in_memory_psd(const LogArguments& args, const WelchOptions& welch) {
  LogPsd out;
  out.input = load_channels(args);
  LoadedChannels& loaded = out.input;
  check_phase_length(loaded.kind, static_cast<std::int64_t>(loaded.log.channels.front().size()));
  const std::vector<std::int64_t>& starts = loaded.log.timing.segment_starts;
  out.outlier_warnings = outlier_warnings(loaded.log.channels, loaded.log.channel_names,
                                          loaded.channel_units, loaded.kind);
  for (std::size_t c = 0; c < loaded.log.channels.size(); ++c) {
    auto& channel = loaded.log.channels[c];
    // The samples are in SI here (load_channels): the constant value back in the input unit.
    auto value = whole_run_value(check_runs(channel, loaded.log.channel_names[c]),
                           static_cast<std::int64_t>(channel.size()));
    if (value) *value /= loaded.to_si;
    out.constant_value.push_back(value);
    if (starts.size() > 1) {
      std::vector<std::vector<double>> rates;
      for (std::size_t k = 0; k < starts.size(); ++k) {
        const auto end = k + 1 < starts.size() ? starts[k + 1]
                                               : static_cast<std::int64_t>(channel.size());
        std::vector<double> part(channel.begin() + starts[k], channel.begin() + end);
        if (loaded.kind == DataKind::phase && part.size() < 2) continue;  // no rate sample
        rates.push_back(to_rate_series(std::move(part), loaded.kind, loaded.rate_hz));
      }
      std::vector<double>().swap(channel);
      const std::vector<std::span<const double>> stretches(rates.begin(), rates.end());
      out.curves.push_back(for_channel(args.input, loaded.log.channel_names[c], [&] {
        return welch_psd_stretches(stretches, loaded.rate_hz, welch);
      }));
      continue;
    }
    const auto rate = to_rate_series(std::move(channel), loaded.kind, loaded.rate_hz);
    std::vector<double>().swap(channel);
    out.curves.push_back(for_channel(args.input, loaded.log.channel_names[c],
                                     [&] { return welch_psd(rate, loaded.rate_hz, welch); }));
  }
  return out;
}

/// One read pass. Returns the PSDs, or nullopt with `recount` set to the rows read when the
/// segment length came from a stated row count that turned out to choose another length.
std::optional<LogPsd> stream_pass(const LogArguments& args, const LogOptions& options,
                                  const WelchOptions& welch, std::int64_t memory_bytes,
                                  std::optional<std::int64_t> known_rows, std::int64_t& recount) {
  LogReader reader(options);
  LogPsd out;
  LoadedChannels& input = out.input;
  set_input_unit(args, input);
  input.log.path = options.path;
  input.log.channel_names = reader.channel_names();
  const std::size_t channels = input.log.channel_names.size();
  const DataKind kind = input.kind;

  // The segment length when it is known before the end; `checked` when it rests on a count the
  // input stated, to be compared with the rows actually read.
  std::int64_t length = welch.segment_length;
  bool checked = false;
  if (length == 0 && known_rows) length = default_segment_length(rate_count(*known_rows, kind));
  if (length == 0) {
    const std::int64_t stated = stated_rows(options, reader.timing());
    if (stated >= 0) {
      length = default_segment_length(rate_count(stated, kind));
      checked = true;
    }
  }
  const bool rate_from_time = !args.rate_hz && reader.has_time();
  const std::int64_t saturated = kDefaultSegmentSaturation;
  const std::int64_t held_limit =
      std::max<std::int64_t>(1, memory_bytes / static_cast<std::int64_t>(8 * channels));

  std::vector<std::vector<double>> held(channels);
  std::int64_t rows = 0;
  std::vector<ChannelFeed> feeds;
  // The outlier check sees the values as the feeds leave them (x to_si), as in memory.
  BlockOutliers outliers(args, kind);
  const auto start = [&](std::int64_t segment_length) {
    input.rate_hz = resolve_rate_hz(args.rate_hz, reader.timing(), args.input);
    WelchOptions fixed = welch;
    fixed.segment_length = segment_length;
    feeds.reserve(channels);
    for (std::size_t c = 0; c < channels; ++c) {
      feeds.emplace_back(input.log.channel_names[c], input.rate_hz, fixed, kind, input.to_si);
      feeds.back().add(held[c]);
    }
    outliers.add(input.log.channel_names, held, false);  // up to --memory: checked in place
    for (auto& values : held) std::vector<double>().swap(values);
  };

  SampleBlock block;
  Progress progress;
  while (reader.read_block(block)) {
    rows += block.rows();
    progress.update(reader.bytes_read(), reader.total_bytes());
    if (!feeds.empty()) {
      for (std::size_t c = 0; c < channels; ++c) feeds[c].add(block.values[c]);
      outliers.add(input.log.channel_names, block.values);
      continue;
    }
    for (std::size_t c = 0; c < channels; ++c) {
      held[c].insert(held[c].end(), block.values[c].begin(), block.values[c].end());
    }
    if (rate_from_time && rows < kRateStamps) continue;  // the rate is not final yet
    if (length > 0) {
      start(length);
    } else if (rate_count(rows, kind) >= saturated) {
      start(default_segment_length(saturated));
    } else if (rows > held_limit) {
      if (!rereadable(options.path)) {
        throw Error(std::string(options.path == "-" ? "<stdin>" : options.path) +
                    ": more than --memory holds before the default segment length can be chosen "
                    "(it depends on the length of the log, which a pipe does not tell): give "
                    "--segment N or a larger --memory");
      }
      progress.finish();
      const std::int64_t total = count_rows(options);
      length = default_segment_length(rate_count(total, kind));
      checked = true;
      start(length);
    }
  }
  progress.finish();
  input.log.timing = reader.timing();
  if (rows == 0) {
    throw ParseError(options.path == "-" ? "<stdin>" : options.path, 0, 0,
                     "no samples: the input holds no data rows");
  }
  check_phase_length(kind, rows);
  if (feeds.empty()) {
    // The log ended within the held blocks: its length is known.
    start(welch.segment_length > 0 ? welch.segment_length
                                   : default_segment_length(rate_count(rows, kind)));
  } else if (checked && default_segment_length(rate_count(rows, kind)) != length) {
    recount = rows;
    return std::nullopt;
  }
  for (std::size_t c = 0; c < feeds.size(); ++c) {
    ChannelFeed& feed = feeds[c];
    out.curves.push_back(
        for_channel(args.input, input.log.channel_names[c], [&] { return feed.result(); }));
    out.constant_value.push_back(feed.constant_value());
  }
  out.outlier_warnings = outliers.finish();
  resolve_channel_units(args, input);
  return out;
}

}  // namespace

LogPsd log_psd(const LogArguments& args, const WelchOptions& welch, std::int64_t memory_bytes) {
  const LogOptions options = log_options_from(args);
  if (options.gaps == GapPolicy::fill || options.gaps == GapPolicy::split)
    return in_memory_psd(args, welch);
  std::optional<std::int64_t> known_rows;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    std::int64_t recount = 0;
    if (auto psd = stream_pass(args, options, welch, memory_bytes, known_rows, recount)) {
      note_reading(args, options, psd->input.log.timing);
      return std::move(*psd);
    }
    known_rows = recount;
  }
  throw Error(args.input + ": the input changed length between read passes");
}

}  // namespace sigmatau::cli
