// LogReader: opens the input (file, stdin, gzip, or a ROS bag), hands it to the text, binary or
// bag reader and accumulates the timing report. The readers live in text_log.cpp, binary_log.cpp
// and bag_log.cpp.
#include "sigmatau/log_reader.hpp"

#include <cmath>
#include <cstdio>

#include "bag_log.hpp"
#include "binary_log.hpp"
#include "byte_source.hpp"
#include "log_internal.hpp"
#include "page_populate.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/text_encoding.hpp"
#include "text_log.hpp"

namespace sigmatau {
namespace {

/// Largest read buffer accepted [bytes]: beyond 1 GiB a bigger buffer buys nothing and a typo
/// would ask for absurd memory.
constexpr std::int64_t kMaxBufferBytes = std::int64_t{1} << 30;
/// A text file's rows estimated from the bytes per row of its first block, with this margin for
/// longer rows later on (more digits, a longer time stamp): reserved address space, of which
/// only what is written becomes memory.
constexpr double kRowEstimateMargin = 1.25;
/// Fewest bytes of a bag per sensor_msgs/Imu message: its 37 doubles alone take 296, and no
/// chunk compression of them reaches 9x.
constexpr std::int64_t kMinBagMessageBytes = 32;
/// Most rows reserved from an estimate (2^32, 32 GiB a channel): beyond, the arrays grow.
constexpr std::int64_t kMaxReservedRows = std::int64_t{1} << 32;
/// Rows added to that estimate, for a short last piece.
constexpr double kRowEstimateSlack = 1024;

}  // namespace

TimeUnit parse_time_unit(std::string_view text) {
  if (text == "s") return TimeUnit::s;
  if (text == "ms") return TimeUnit::ms;
  if (text == "us") return TimeUnit::us;
  if (text == "ns") return TimeUnit::ns;
  if (text == "min") return TimeUnit::min;
  if (text == "h") return TimeUnit::h;
  if (text == "d") return TimeUnit::d;
  throw Error("unknown time unit \"" + std::string(text) +
              "\" (expected s, ms, us, ns, min, h or d)");
}

BinaryFormat parse_binary_format(std::string_view text) {
  if (text == "i16") return BinaryFormat::i16;
  if (text == "i32") return BinaryFormat::i32;
  if (text == "f32") return BinaryFormat::f32;
  if (text == "f64") return BinaryFormat::f64;
  throw Error("unknown binary format \"" + std::string(text) +
              "\" (expected i16, i32, f32 or f64)");
}

std::int64_t value_bytes(BinaryFormat format) {
  switch (format) {
    case BinaryFormat::i16:
      return 2;
    case BinaryFormat::i32:
    case BinaryFormat::f32:
      return 4;
    case BinaryFormat::f64:
      return 8;
    case BinaryFormat::none:
      break;
  }
  throw Error("binary log: no binary format given");
}

TruncatedPolicy parse_truncated_policy(std::string_view text) {
  if (text == "error") return TruncatedPolicy::error;
  if (text == "use") return TruncatedPolicy::use;
  throw Error("unknown --truncated value \"" + std::string(text) + "\" (expected error or use)");
}

struct LogReader::Impl {
  std::unique_ptr<detail::ByteSource> source;  // text and binary input
  detail::TimingAccumulator timing;
  std::unique_ptr<detail::TextLog> text;
  std::unique_ptr<detail::BinaryLog> binary;
  std::unique_ptr<detail::BagLog> bag;
  const detail::ColumnSelection* selection = nullptr;
  bool finished = false;
  std::int64_t rows_delivered = 0;
  mutable bool report_stale = true;
  mutable TimingReport report;

  explicit Impl(const LogOptions& options) {
    if (is_bag_path(options.path)) {
      bag = std::make_unique<detail::BagLog>(options, timing);
      selection = &bag->selection();
      return;
    }
    source = std::make_unique<detail::ByteSource>(options.path);
    if (!(options.read_buffer_bytes >= 0 && options.read_buffer_bytes <= kMaxBufferBytes)) {
      throw Error("read_buffer_bytes must be in 0.." + std::to_string(kMaxBufferBytes) + ", got " +
                  std::to_string(options.read_buffer_bytes));
    }
    const std::size_t buffer_bytes = options.read_buffer_bytes > 0
                                         ? static_cast<std::size_t>(options.read_buffer_bytes)
                                         : detail::kDefaultBufferBytes;
    if (options.binary != BinaryFormat::none) {
      binary = std::make_unique<detail::BinaryLog>(*source, options, buffer_bytes, timing);
      selection = &binary->selection();
    } else {
      text = std::make_unique<detail::TextLog>(*source, options, buffer_bytes, timing);
      selection = &text->selection();
    }
    timing.start(selection->has_time, selection->time_unit);
  }
};

LogReader::LogReader(const LogOptions& options) : impl_(std::make_unique<Impl>(options)) {}
LogReader::~LogReader() = default;

const std::vector<std::string>& LogReader::channel_names() const {
  return impl_->selection->channel_names;
}

bool LogReader::has_time() const { return impl_->selection->has_time; }

bool LogReader::read_block(SampleBlock& block, std::int64_t max_rows) {
  Impl& m = *impl_;
  if (!(max_rows >= 1)) throw Error("read_block: max_rows must be >= 1");
  const std::size_t channels = m.selection->channel_columns.size();
  block.values.resize(channels);
  const auto reserve = static_cast<std::size_t>(std::min<std::int64_t>(max_rows, 65536));
  for (auto& v : block.values) {
    v.clear();
    v.reserve(reserve);
  }
  block.t_s.clear();
  if (m.selection->has_time) block.t_s.reserve(reserve);
  return append_block(block, max_rows);
}

bool LogReader::append_block(SampleBlock& block, std::int64_t max_rows) {
  Impl& m = *impl_;
  if (!(max_rows >= 1)) throw Error("append_block: max_rows must be >= 1");
  const std::size_t channels = m.selection->channel_columns.size();
  if (block.values.empty()) block.values.resize(channels);
  if (block.values.size() != channels) {
    throw Error("append_block: the block holds " + std::to_string(block.values.size()) +
                " channels, the input " + std::to_string(channels));
  }
  if (m.finished) return false;
  const std::int64_t rows = m.bag    ? m.bag->read_rows(block, max_rows)
                            : m.text ? m.text->read_rows(block, max_rows)
                                     : m.binary->read_rows(block, max_rows);
  m.report_stale = true;
  m.rows_delivered += rows;
  if (rows == 0) {
    m.finished = true;
    try {
      m.timing.finish();
    } catch (const ParseError& e) {
      // A gap left by skipped bag messages: the error says what the reader skipped.
      const std::vector<std::string> met = m.bag ? m.bag->warnings() : std::vector<std::string>{};
      if (met.empty()) throw;
      std::string also;
      for (const std::string& w : met) also += "; while reading: " + w;
      throw ParseError(e.file(), e.line(), e.column(), e.message() + also);
    }
    return false;
  }
  return true;
}

const TimingReport& LogReader::timing() const {
  if (impl_->report_stale) {
    impl_->report = impl_->timing.report();
    if (impl_->bag) {
      impl_->report.reordered_samples = impl_->bag->reordered_samples();
      impl_->report.max_reorder_s = impl_->bag->max_reorder_s();
      // Topic names and types go into every output: UTF-8, as column names are.
      const auto utf8 = [](const std::string& s) {
        return is_utf8(s) ? s : utf8_from_windows1252(s);
      };
      impl_->report.bag_topic = utf8(impl_->bag->topic());
      impl_->report.bag_topics = impl_->bag->topics_listed();
      for (BagTopic& t : impl_->report.bag_topics) {
        t.name = utf8(t.name);
        t.type = utf8(t.type);
      }
      const detail::BagCut& cut = impl_->bag->cut();
      if (cut.at_byte >= 0) {
        impl_->report.truncated_at_byte = cut.at_byte;
        impl_->report.truncated_file = cut.file;
      }
    }
    impl_->report.warnings = impl_->selection->warnings;
    if (impl_->bag) {
      for (std::string& w : impl_->bag->warnings()) impl_->report.warnings.push_back(std::move(w));
    }
    impl_->report_stale = false;
  }
  return impl_->report;
}

std::int64_t LogReader::bytes_read() const {
  return impl_->bag ? impl_->bag->bytes_read() : impl_->source->bytes_consumed();
}
std::int64_t LogReader::total_bytes() const {
  return impl_->bag ? impl_->bag->total_bytes() : impl_->source->total_bytes();
}
std::int64_t LogReader::rows_left_hint() const {
  const Impl& m = *impl_;
  if (m.binary) return m.binary->records_left();
  if (m.bag) {
    // The rows a bag holds: its stated count of the topic's messages (each a row), an upper
    // bound when some are skipped (non-finite values). A count no bag of this size could hold
    // (a corrupt index) is no hint.
    const std::int64_t stated = m.bag->messages_stated();
    const std::int64_t most = std::min(kMaxReservedRows, m.bag->total_bytes() / kMinBagMessageBytes);
    if (stated > most) return -1;
    return stated > m.rows_delivered ? stated - m.rows_delivered : -1;
  }
  if (!m.text || m.source->gzip() || m.rows_delivered == 0) return -1;
  const std::int64_t total = m.source->total_bytes();
  const std::int64_t done = m.source->bytes_consumed();
  if (!(total > 0 && done > 0)) return -1;
  // The reader's buffer runs ahead of the rows delivered: the bytes per row come out high and
  // the estimate low, which the margin covers for rows of even length.
  const double per_row = static_cast<double>(done) / static_cast<double>(m.rows_delivered);
  const double estimate =
      kRowEstimateMargin * static_cast<double>(total - done) / per_row + kRowEstimateSlack;
  return estimate < static_cast<double>(kMaxReservedRows) ? static_cast<std::int64_t>(estimate)
                                                          : -1;
}

Log read_log(const LogOptions& options,
             const std::function<void(std::int64_t, std::int64_t)>& progress) {
  LogReader reader(options);
  Log log;
  log.path = options.path;
  log.channel_names = reader.channel_names();
  log.channels.resize(log.channel_names.size());
  // The final arrays are sized once: where the input tells its length (a raw binary file) before
  // the first block, else from the bytes per row of the first block (a plain text file;
  // generous, since capacity never written costs address space, not memory). Grown by
  // reallocation instead, every step copies all that was read and holds both copies at once.
  // One row more than the input holds: a rate channel's phase has one point more than its
  // samples, so the samples' memory can then hold an array of the phase (PhaseSeries::recycle).
  // The blocks are read straight into the final arrays (LogReader::append_block).
  SampleBlock all;
  all.values.resize(log.channel_names.size());
  const auto reserve_rows = [&](std::int64_t rows) {
    const auto size = static_cast<std::size_t>(rows) + 1 +
                      (all.values.empty() ? 0 : all.values[0].size());
    for (auto& channel : all.values) channel.reserve(size);
    if (reader.has_time()) all.t_s.reserve(size);
  };
  bool sized = false;
  if (const std::int64_t hint = reader.rows_left_hint(); hint > 0) {
    // Known before the first block (a raw binary file): the exact length, so every page
    // reserved will be written; they are faulted in on the other core meanwhile.
    reserve_rows(hint);
    sized = true;
    for (auto& channel : all.values) {
      detail::populate_in_background(channel.data(), channel.capacity() * sizeof(double));
    }
  }
  while (reader.append_block(all)) {
    if (!sized) {
      sized = true;
      if (const std::int64_t hint = reader.rows_left_hint(); hint > 0) reserve_rows(hint);
    }
    if (progress) progress(reader.bytes_read(), reader.total_bytes());
  }
  log.channels = std::move(all.values);
  log.t_s = std::move(all.t_s);
  log.timing = reader.timing();
  if (log.channels.empty() || log.channels[0].empty()) {
    throw ParseError(options.path == "-" ? "<stdin>" : options.path, 0, 0,
                     "no samples: the input holds no data rows" +
                         std::string(log.timing.rows_skipped_nonfinite > 0
                                         ? " (every row held a non-finite value and was skipped)"
                                         : ""));
  }
  return log;
}

double resolve_rate_hz(std::optional<double> rate_hz, const TimingReport& timing,
                       const std::string& path) {
  if (rate_hz) return checked_rate_hz(*rate_hz, "rate_hz");
  if (!timing.has_time) {
    throw Error(path +
                ": no --rate and no time column: give the sample rate (--rate HZ) or the "
                "time stamp column (--time-column NAME)");
  }
  if (!(timing.rate_hz > 0)) {
    throw Error(path +
                ": cannot measure the sample rate from the time column (fewer than 2 "
                "stamps, or the median interval is not > 0); give --rate HZ");
  }
  if (!(timing.rate_hz >= kMinRateHz && timing.rate_hz <= kMaxRateHz)) {
    char text[300];
    std::snprintf(text, sizeof text,
                  ": the time column's stamps are %.6g s apart (median), a rate of %.6g Hz, "
                  "outside the rates sigmatau computes with (%g to %g Hz); check the time "
                  "column and the unit of its stamps",
                  1 / timing.rate_hz, timing.rate_hz, kMinRateHz, kMaxRateHz);
    throw Error(path + text);
  }
  return timing.rate_hz;
}

}  // namespace sigmatau
