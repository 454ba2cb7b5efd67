// Internal: raw binary log decoding. Records are C values of one type, channel after channel;
// the buffer holds whole records plus at most one partial record carried to the next read.
#include "binary_log.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

std::size_t value_size(BinaryFormat f) { return static_cast<std::size_t>(value_bytes(f)); }

inline std::uint16_t bswap(std::uint16_t v) { return __builtin_bswap16(v); }
inline std::uint32_t bswap(std::uint32_t v) { return __builtin_bswap32(v); }
inline std::uint64_t bswap(std::uint64_t v) { return __builtin_bswap64(v); }

template <std::size_t N>
struct UnsignedOf;
template <>
struct UnsignedOf<2> {
  using type = std::uint16_t;
};
template <>
struct UnsignedOf<4> {
  using type = std::uint32_t;
};
template <>
struct UnsignedOf<8> {
  using type = std::uint64_t;
};

template <class T, bool kSwap>
inline double load(const char* p) {
  using U = typename UnsignedOf<sizeof(T)>::type;
  U u;
  std::memcpy(&u, p, sizeof u);
  if constexpr (kSwap) u = bswap(u);
  return static_cast<double>(std::bit_cast<T>(u));
}

}  // namespace

BinaryLog::BinaryLog(ByteSource& source, const LogOptions& options, std::size_t buffer_bytes,
                     TimingAccumulator& timing)
    : source_(source),
      timing_(timing),
      nonfinite_(options.nonfinite),
      format_(options.binary),
      swap_(options.big_endian != (std::endian::native == std::endian::big)),
      value_bytes_(value_size(options.binary)),
      record_bytes_(0),
      skip_bytes_(options.skip_bytes) {
  const std::string& name = source_.name();
  if (!(options.binary_channels >= 1 &&
        static_cast<std::size_t>(options.binary_channels) <= kMaxColumns)) {
    throw Error(name + ": binary input needs 1.." + std::to_string(kMaxColumns) +
                " channels, got " + std::to_string(options.binary_channels));
  }
  if (!(options.skip_bytes >= 0)) throw Error(name + ": skip_bytes must be >= 0");
  if (!options.time_column.empty()) {
    throw Error(name + ": a time column needs text input; give the sample rate for binary input");
  }
  const auto channels = static_cast<std::size_t>(options.binary_channels);
  record_bytes_ = channels * value_bytes_;
  const std::size_t records_per_read = std::max<std::size_t>(1, buffer_bytes / record_bytes_);
  buffer_.resize((records_per_read + 1) * record_bytes_);

  const std::vector<std::string> names(channels);
  const std::vector<bool> numeric(channels, true);
  selection_ = select_columns(names, false, numeric, options, name, 0, 0, "channel");
  row_.assign(selection_.channel_columns.size(), 0.0);

  // Skip the header by reading it (works for pipes and gzip alike).
  std::int64_t left = skip_bytes_;
  while (left > 0) {
    const auto want = static_cast<std::size_t>(
        std::min<std::int64_t>(left, static_cast<std::int64_t>(buffer_.size())));
    const std::size_t got = source_.read(buffer_.data(), want);
    if (got == 0) {
      throw ParseError(name, 0, 0,
                       "the input ends at byte " + std::to_string(skip_bytes_ - left) +
                           ", inside the " + std::to_string(skip_bytes_) + "-byte header to skip");
    }
    left -= static_cast<std::int64_t>(got);
  }
  if (!fill()) {
    throw ParseError(
        name, 0, 0,
        "no data rows: no bytes after the " + std::to_string(skip_bytes_) + "-byte header");
  }
}

bool BinaryLog::fill() {
  if (end_ - pos_ >= record_bytes_) return true;
  const std::size_t keep = end_ - pos_;
  if (keep > 0 && pos_ != 0) std::memmove(buffer_.data(), buffer_.data() + pos_, keep);
  pos_ = 0;
  end_ = keep;
  while (!eof_ && end_ < record_bytes_) {
    const std::size_t got = source_.read(buffer_.data() + end_, buffer_.size() - end_);
    if (got == 0) eof_ = true;
    end_ += got;
  }
  if (end_ >= record_bytes_) return true;
  if (end_ == 0) return false;
  const std::int64_t offset = skip_bytes_ + records_ * static_cast<std::int64_t>(record_bytes_);
  throw ParseError(source_.name(), 0, 0,
                   "truncated record at byte offset " + std::to_string(offset) + ": expected " +
                       std::to_string(record_bytes_) + "-byte records (" +
                       std::to_string(record_bytes_ / value_bytes_) + " channels x " +
                       std::to_string(value_bytes_) + " bytes), found " + std::to_string(end_) +
                       " bytes at the end");
}

template <class T, bool kSwap>
std::int64_t BinaryLog::decode(SampleBlock& block, std::int64_t records) {
  const std::size_t channels = row_.size();
  const int* const columns = selection_.channel_columns.data();
  // Channel by channel into the block, when every value is finite (the common case): a tight
  // loop per channel instead of a push per value. Otherwise the block is put back as it was and
  // the records go one by one through the loop below, which skips or refuses them.
  const char* const first = buffer_.data() + pos_;
  bool all_finite = true;
  for (std::size_t k = 0; k < channels && all_finite; ++k) {
    std::vector<double>& out = block.values[k];
    const std::size_t base = out.size();
    out.resize(base + static_cast<std::size_t>(records));
    double* const to = out.data() + base;
    const char* from = first + static_cast<std::size_t>(columns[k]) * sizeof(T);
    double finite_check = 0.0;  // stays 0 unless some value is NaN or infinite
    for (std::int64_t r = 0; r < records; ++r, from += record_bytes_) {
      const double v = load<T, kSwap>(from);
      to[r] = v;
      if constexpr (std::is_floating_point_v<T>) finite_check += v * 0.0;
    }
    if (!(finite_check == 0.0)) {
      all_finite = false;
      for (std::size_t j = 0; j <= k; ++j) {
        block.values[j].resize(block.values[j].size() - static_cast<std::size_t>(records));
      }
    }
  }
  if (all_finite) return records;
  std::int64_t kept = 0;
  for (std::int64_t r = 0; r < records; ++r) {
    const char* rec = buffer_.data() + pos_ + static_cast<std::size_t>(r) * record_bytes_;
    bool finite = true;
    for (std::size_t k = 0; k < channels; ++k) {
      row_[k] = load<T, kSwap>(rec + static_cast<std::size_t>(columns[k]) * sizeof(T));
      if constexpr (std::is_floating_point_v<T>) finite &= std::isfinite(row_[k]);
    }
    if (!finite) {
      if (nonfinite_ == NonFinitePolicy::skip_row) {
        timing_.add_skipped();
        continue;
      }
      for (std::size_t k = 0; k < channels; ++k) {
        if (std::isfinite(row_[k])) continue;
        const std::int64_t offset = skip_bytes_ +
                                    (records_ + r) * static_cast<std::int64_t>(record_bytes_) +
                                    columns[k] * static_cast<std::int64_t>(sizeof(T));
        throw ParseError(source_.name(), 0, columns[k] + 1,
                         "non-finite value (NaN or Inf) in channel " + selection_.channel_names[k] +
                             " of record " + std::to_string(records_ + r) + " at byte offset " +
                             std::to_string(offset));
      }
    }
    for (std::size_t k = 0; k < channels; ++k) block.values[k].push_back(row_[k]);
    ++kept;
  }
  return kept;
}

std::int64_t BinaryLog::records_left() const {
  if (source_.gzip() || source_.total_bytes() < 0) return -1;
  const std::int64_t bytes = source_.total_bytes() - skip_bytes_;
  return std::max<std::int64_t>(
      0, bytes / static_cast<std::int64_t>(record_bytes_) - records_);
}

std::int64_t BinaryLog::read_rows(SampleBlock& block, std::int64_t max_rows) {
  std::int64_t rows = 0;
  const std::int64_t held = block.rows();  // rows the block held before this call
  try {
    read_records(block, max_rows, rows);
  } catch (...) {
    timing_.add_untimed(block.rows() - held);  // the whole rows decoded before the error count
    throw;
  }
  timing_.add_untimed(rows);
  return rows;
}

void BinaryLog::read_records(SampleBlock& block, std::int64_t max_rows, std::int64_t& rows) {
  while (rows < max_rows && fill()) {
    const auto available = static_cast<std::int64_t>((end_ - pos_) / record_bytes_);
    const std::int64_t n = std::min(available, max_rows - rows);
    std::int64_t kept = 0;
    switch (format_) {
      case BinaryFormat::i16:
        kept = swap_ ? decode<std::int16_t, true>(block, n) : decode<std::int16_t, false>(block, n);
        break;
      case BinaryFormat::i32:
        kept = swap_ ? decode<std::int32_t, true>(block, n) : decode<std::int32_t, false>(block, n);
        break;
      case BinaryFormat::f32:
        kept = swap_ ? decode<float, true>(block, n) : decode<float, false>(block, n);
        break;
      case BinaryFormat::f64:
        kept = swap_ ? decode<double, true>(block, n) : decode<double, false>(block, n);
        break;
      case BinaryFormat::none:
        break;
    }
    pos_ += static_cast<std::size_t>(n) * record_bytes_;
    records_ += n;
    rows += kept;
  }
}

}  // namespace sigmatau::detail
